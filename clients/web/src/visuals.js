// How a body looks when its description says so (a robot link's URDF
// <visual> elements, body_description_t.visuals): boxes, spheres, cylinders
// and mesh files in their URDF colours, drawn instead of the collision shape.
//
// Mesh files come from the bridge that served the page, under /meshes/ (the
// visual's mesh_url is relative to that route, rbview_bridge/meshes.py), read
// by three.js's own loaders, bundled with the page: STL, OBJ (its geometry;
// the URDF's colour, as ROS tools do without a material file) and COLLADA
// (its own materials unless the URDF gives a colour). Each file is fetched and
// parsed once per page and shared by every visual that names it.
//
// Frames (lcmtypes/rbsim/visual_t.lcm): p_shape = R(orientation) p_visual +
// position, in the body's shape frame; URDF cylinders lie along z, three.js's
// along y. A COLLADA file is placed in its link's frame as rbserver reads it
// (server/meshio/collada_mesh.cpp, whose collision shape it must match): its
// <unit meter> applied, Z_UP kept, Y_UP and X_UP turned to z up. ColladaLoader
// does otherwise (Z_UP turned to y up, the others left as they are, an
// <up_axis> with spaces around its value taken for Y_UP), so the file's asset
// is read here and the loader's root transform replaced.
import * as THREE from "three";
import { STLLoader } from "three/examples/jsm/loaders/STLLoader.js";
import { OBJLoader } from "three/examples/jsm/loaders/OBJLoader.js";
import { ColladaLoader } from "three/examples/jsm/loaders/ColladaLoader.js";

export const MESH_ROUTE = "/meshes/";
const DEFAULT_COLOR = new THREE.Color(0xb8bcc4); // a visual without a colour of its own
const SEGMENTS = 32;

// Whether the body is drawn from its visuals: it has some, and every mesh
// among them can be fetched (one that cannot, the server says, lies outside
// the directories the bridge serves: then the collision shape, whole).
export function drawsVisuals(body) {
  const visuals = body.visuals || [];
  return visuals.length > 0 && visuals.every((v) => v.kind !== "mesh" || v.mesh_url);
}

function meshUrlOf(relative) {
  // Each component escaped: a file name may hold '#', '?' or spaces.
  return MESH_ROUTE + relative.split("/").map(encodeURIComponent).join("/");
}

function extensionOf(url) {
  const dot = url.lastIndexOf(".");
  return dot < 0 ? "" : url.slice(dot + 1).toLowerCase();
}

// A COLLADA document's <asset> settings as rbserver reads them
// (server/meshio/collada_guard.cpp): metres per unit and up axis, COLLADA's
// defaults (1, Y_UP) when absent; a value it would refuse is an error here too.
function colladaAsset(text) {
  const root = new DOMParser().parseFromString(text, "application/xml").documentElement;
  const asset = { metres: 1, up: "Y_UP" };
  const info = [...root.children].find((e) => e.nodeName === "asset");
  if (!info) return asset;
  const unit = [...info.children].find((e) => e.nodeName === "unit");
  if (unit && unit.hasAttribute("meter")) {
    const value = unit.getAttribute("meter").trim();
    const metres = Number(value);
    if (value === "" || !Number.isFinite(metres) || metres <= 0) {
      throw new Error(`<unit meter="${value.slice(0, 40)}"> is not a positive finite number`);
    }
    asset.metres = metres;
  }
  const up = [...info.children].find((e) => e.nodeName === "up_axis");
  if (up) {
    asset.up = up.textContent.trim();
    if (!["X_UP", "Y_UP", "Z_UP"].includes(asset.up)) {
      throw new Error(`<up_axis> is "${asset.up.slice(0, 40)}", not X_UP, Y_UP or Z_UP`);
    }
  }
  return asset;
}

// The file's axes to its link's: rows of rbserver's sceneToWorld rotation.
const UP_AXIS_ROTATIONS = {
  Z_UP: new THREE.Matrix4(),
  Y_UP: new THREE.Matrix4().set(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1), // +y becomes +z
  X_UP: new THREE.Matrix4().set(0, -1, 0, 0, 0, 0, -1, 0, 1, 0, 0, 0, 0, 0, 0, 1), // +x becomes +z, +y becomes -x
};

async function loadCollada(url) {
  const text = await new THREE.FileLoader().loadAsync(url);
  const asset = colladaAsset(text);
  const { scene } = new ColladaLoader().parse(text, THREE.LoaderUtils.extractUrlBase(url));
  scene.quaternion.setFromRotationMatrix(UP_AXIS_ROTATIONS[asset.up]);
  scene.scale.setScalar(asset.metres);
  scene.updateMatrix();
  // A file's own lights and cameras would light the whole world from inside a link.
  const strays = [];
  scene.traverse((o) => { if (o.isLight || o.isCamera) strays.push(o); });
  for (const o of strays) o.removeFromParent();
  // A file without normals (rbserver needs none) would be drawn black.
  scene.traverse((o) => {
    if (o.isMesh && !o.geometry.hasAttribute("normal")) o.geometry.computeVertexNormals();
  });
  return scene;
}

// url -> Promise of {geometry} (STL), {object} (OBJ, COLLADA).
const loaded = new Map();
function loadMesh(url) {
  if (loaded.has(url)) return loaded.get(url);
  const kind = extensionOf(url);
  const promise = (async () => {
    if (kind === "stl") {
      const geometry = await new STLLoader().loadAsync(url);
      if (!geometry.hasAttribute("normal")) geometry.computeVertexNormals();
      return { geometry };
    }
    if (kind === "obj") return { object: await new OBJLoader().loadAsync(url) };
    if (kind === "dae") return { object: await loadCollada(url) };
    throw new Error(`${url}: not STL, OBJ or COLLADA`);
  })();
  loaded.set(url, promise);
  return promise;
}

function materialOf(visual) {
  const material = new THREE.MeshStandardMaterial({ color: DEFAULT_COLOR, roughness: 0.55, metalness: 0.1 });
  if (visual.has_color) {
    // URDF's rgba is linear, as three.js's working colour space.
    material.color.setRGB(visual.rgba[0], visual.rgba[1], visual.rgba[2]);
    if (visual.rgba[3] < 1) {
      material.transparent = true;
      material.opacity = visual.rgba[3];
    }
  }
  return material;
}

function castsShadows(object, body) {
  object.traverse((o) => {
    if (o.isMesh) {
      o.castShadow = true;
      o.receiveShadow = true;
      o.userData.body = body;
    }
  });
}

// One visual in the shape frame (before its mesh has arrived: an empty group
// that it is added to).
function visualObject(visual, body, pending) {
  const placed = new THREE.Group();
  placed.position.set(...visual.position);
  // Wire order (w, x, y, z); three.js takes (x, y, z, w).
  const q = visual.orientation;
  placed.quaternion.set(q[1], q[2], q[3], q[0]).normalize();
  const material = materialOf(visual);
  let geometry = null;
  if (visual.kind === "box") {
    const h = visual.half_extents;
    geometry = new THREE.BoxGeometry(2 * h[0], 2 * h[1], 2 * h[2]);
  } else if (visual.kind === "sphere") {
    geometry = new THREE.SphereGeometry(visual.radius, SEGMENTS, SEGMENTS / 2);
  } else if (visual.kind === "cylinder") {
    geometry = new THREE.CylinderGeometry(visual.radius, visual.radius, 2 * visual.half_length, SEGMENTS)
      .rotateX(Math.PI / 2);
  }
  if (geometry) {
    const mesh = new THREE.Mesh(geometry, material);
    placed.add(mesh);
    castsShadows(placed, body);
    return placed;
  }
  if (visual.kind !== "mesh" || !visual.mesh_url) return placed;
  placed.scale.set(...visual.scale);
  const url = meshUrlOf(visual.mesh_url);
  pending.count++;
  loadMesh(url).then(({ geometry: shared, object }) => {
    let drawn;
    if (shared) {
      drawn = new THREE.Mesh(shared, material);
    } else {
      drawn = object.clone(true);
      // OBJ without its material file, or a COLLADA file under a URDF colour;
      // otherwise the file's materials, copied: selecting a body tints its
      // own, not every body drawn from the same file.
      const own = extensionOf(url) === "obj" || visual.has_color;
      drawn.traverse((o) => {
        if (!o.isMesh) return;
        if (own) o.material = material;
        else o.material = Array.isArray(o.material) ? o.material.map((m) => m.clone()) : o.material.clone();
      });
    }
    castsShadows(drawn, body);
    placed.add(drawn);
    const kind = extensionOf(url);
    pending.drawn[kind] = (pending.drawn[kind] || 0) + 1;
  }).catch((error) => {
    pending.failed.push(`${visual.mesh_url}: ${error.message || error}`);
    pending.failedBodies.add(body);
    console.warn(`rbview: visual mesh ${visual.mesh_url} not drawn: ${error.message || error}`);
  }).finally(() => { pending.count--; pending.changed = true; });
  return placed;
}

// The body's visuals as one object in its body frame (its matrix is set from
// the state's pose); `pending` counts the meshes still on their way.
export function bodyVisuals(body, index, shapeInBody, pending) {
  const root = new THREE.Group();
  root.matrixAutoUpdate = false;
  const inBody = new THREE.Group();
  inBody.matrixAutoUpdate = false;
  inBody.matrix.copy(shapeInBody);
  root.add(inBody);
  for (const visual of body.visuals) inBody.add(visualObject(visual, index, pending));
  return root;
}

// Tints (or untints) a body's visuals as selected.
export function tintVisuals(root, on) {
  root.traverse((o) => {
    if (o.isMesh && o.material && o.material.emissive) o.material.emissive.setHex(on ? 0x4d3b00 : 0x000000);
  });
}
