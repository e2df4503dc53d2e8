// The 3D view: bodies as instanced pieces, the ground, contacts, joints, the
// push arrow; orbit/pan/zoom, picking and following a body. World frame z up.
//
// A body with visuals (a robot's link, visuals.js) is drawn as itself: its
// visuals, lit by a sun that casts soft shadows (PCFSoftShadowMap) onto them
// and the ground; its collision shape is drawn instead while showCollision is
// on. A world with visuals and no plane gets a ground with a grid at z = 0,
// and its joint markers are subdued until a body is selected. Worlds without
// visuals are drawn as before (no shadow pass).
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { bodyPieces, planeOf, bodySize, shapeFrame } from "./shapes.js";
import { bodyVisuals, drawsVisuals, tintVisuals } from "./visuals.js";
import { SphereImpostors } from "./sphere_impostors.js";
import { JointsView } from "./joints.js";

// Above this many spheres they are drawn as impostors (sphere_impostors.js).
const IMPOSTOR_SPHERES = 200;

const MAX_CONTACTS = 4096;
// Framing (frameAll, frameBody): the bodies' bounding box fills this much of
// the view's height or width, whichever it reaches first, leaving a margin for
// the panels in the corners.
const FRAME_FILL = 0.75;
// The view direction of the first frame, from the target to the camera: from
// the front right and above, as the camera was placed before framing existed.
const DEFAULT_VIEW = new THREE.Vector3(6, -9, 4.5);
// The first view leaves out a body farther than this many times the bodies'
// median distance from their median centre (see gatheredBodies).
const STRAY_DISTANCE = 4;
const NORMAL_LENGTH = 0.15; // m, drawn length of a contact normal
const SELECTED = new THREE.Color(0xffd23f);

function bodyColor(body, index) {
  if (body.is_static) return new THREE.Color(0x8a8f98);
  return new THREE.Color().setHSL(((index * 0.618034) % 1 + 1) % 1, 0.55, 0.55);
}

// The grid on a plane, as THREE.GridHelper draws it (`size` m square, cells of
// size/divisions, the two centre lines in `centreColor`) but lying in x-y and
// made of one-cell segments. In chromium without a GPU (SwiftShader) the 40 m
// lines of GridHelper vanished near the camera when it looked along the ground
// (all of them showed from straight above): it drops a line that reaches
// behind the camera, and the long lines did under any view from over the grid,
// which is where the bodies are.
function cellGrid(size, divisions, centreColor, lineColor) {
  const step = size / divisions;
  const half = size / 2;
  const positions = [];
  const colors = [];
  const centre = new THREE.Color(centreColor);
  const line = new THREE.Color(lineColor);
  for (let i = 0; i <= divisions; i++) {
    const across = -half + i * step;
    const color = 2 * i === divisions ? centre : line;
    for (let j = 0; j < divisions; j++) {
      const from = -half + j * step;
      positions.push(from, across, 0, from + step, across, 0, across, from, 0, across, from + step, 0);
      for (let k = 0; k < 4; k++) colors.push(color.r, color.g, color.b);
    }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.Float32BufferAttribute(positions, 3));
  geometry.setAttribute("color", new THREE.Float32BufferAttribute(colors, 3));
  return new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ vertexColors: true, toneMapped: false }));
}

export class Viewer {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: false, alpha: false, preserveDrawingBuffer: false });
    this.renderer.setPixelRatio(1);
    this.renderer.shadowMap.enabled = true;
    this.renderer.shadowMap.type = THREE.PCFSoftShadowMap;
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x1d2230);
    this.camera = new THREE.PerspectiveCamera(50, 1, 0.05, 2000);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.set(0, 0, 0.5);
    this.camera.position.copy(this.controls.target).add(DEFAULT_VIEW);
    this.controls.update();
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(5, -3, 10);
    sun.shadow.mapSize.set(2048, 2048);
    sun.shadow.bias = -0.0005;
    sun.shadow.normalBias = 0.01;
    sun.shadow.radius = 4;
    this.scene.add(sun, sun.target);
    this.sun = sun;
    this.showCollision = false;
    this.visuals = []; // {body, object}: bodies drawn from their visuals
    // Meshes on their way, those that failed, and those drawn by file kind ({dae: 7}).
    this.visualsPending = { count: 0, failed: [], failedBodies: new Set(), drawn: {}, changed: false };
    this.shadowsFitted = false;
    this.noVisuals = new Set(); // bodies of this world whose visuals failed: drawn from their collision shapes

    this.bodies = [];
    this.groups = []; // {mesh: InstancedMesh, pieces: [{body, local}]}
    this.bodyBounds = []; // per body, the box around its pieces in its own frame; null for planes
    this.planes = []; // {body, object, local}
    this.worldObjects = new THREE.Group();
    this.scene.add(this.worldObjects);
    this.frame = null;
    this.frameDrawn = null;
    this.selected = -1;
    this.follow = false;
    this.showContacts = false;
    this.makeContacts();
    this.joints = new JointsView(this.scene);
    this.arrow = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1, 0xff5533, 0.12, 0.07);
    this.arrow.visible = false;
    this.scene.add(this.arrow);
    this.raycaster = new THREE.Raycaster();
    this.tmpMatrix = new THREE.Matrix4();
    this.tmpPose = new THREE.Matrix4();
    this.tmpPosition = new THREE.Vector3();
    this.tmpQuaternion = new THREE.Quaternion();
    this.unitScale = new THREE.Vector3(1, 1, 1);
    this.resize();
    window.addEventListener("resize", () => this.resize());
  }

  resize() {
    const w = this.container.clientWidth || window.innerWidth;
    const h = this.container.clientHeight || window.innerHeight;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  makeContacts() {
    const points = new THREE.BufferGeometry();
    points.setAttribute("position", new THREE.BufferAttribute(new Float32Array(MAX_CONTACTS * 3), 3));
    this.contactPoints = new THREE.Points(points, new THREE.PointsMaterial({ color: 0xff3355, size: 6, sizeAttenuation: false }));
    const lines = new THREE.BufferGeometry();
    lines.setAttribute("position", new THREE.BufferAttribute(new Float32Array(MAX_CONTACTS * 6), 3));
    this.contactNormals = new THREE.LineSegments(lines, new THREE.LineBasicMaterial({ color: 0xffee55 }));
    for (const o of [this.contactPoints, this.contactNormals]) {
      o.frustumCulled = false;
      o.visible = false;
      this.scene.add(o);
    }
  }

  // `rebuild`: the same world again, the bodies in noVisuals now drawn from
  // their collision shapes (a mesh that could not be fetched or read).
  setWorld(world, rebuild = false) {
    if (!rebuild) this.noVisuals = new Set();
    this.world = world;
    for (const group of this.groups) group.mesh.dispose();
    this.worldObjects.clear();
    this.groups = [];
    this.planes = [];
    this.visuals = [];
    const failed = rebuild ? this.visualsPending.failed : [];
    this.visualsPending = { count: 0, failed, failedBodies: new Set(), drawn: {}, changed: false };
    this.shadowsFitted = false;
    this.bodies = world.bodies;
    this.revision = world.revision;
    this.bodyBounds = [];
    const byKey = new Map();
    world.bodies.forEach((body, index) => {
      const plane = planeOf(body);
      this.bodyBounds.push(null);
      if (plane) {
        this.addPlane(index, plane);
        return;
      }
      const looks = drawsVisuals(body) && !this.noVisuals.has(index);
      if (looks) {
        const object = bodyVisuals(body, index, shapeFrame(body), this.visualsPending);
        object.visible = false; // until a pose arrives
        this.worldObjects.add(object);
        this.visuals.push({ body: index, object });
      }
      for (const piece of bodyPieces(body, world.bodies.length)) {
        // A drawn body's collision shape: its own groups, shown by the toggle.
        const key = looks ? `collision|${piece.key}` : piece.key;
        if (!byKey.has(key)) byKey.set(key, { geometry: piece.geometry(), pieces: [], collision: looks });
        const { geometry, pieces } = byKey.get(key);
        pieces.push({ body: index, local: piece.local });
        if (!geometry.boundingBox) geometry.computeBoundingBox();
        const box = geometry.boundingBox.clone().applyMatrix4(piece.local);
        this.bodyBounds[index] = this.bodyBounds[index] ? this.bodyBounds[index].union(box) : box;
      }
    });
    for (const [key, { geometry, pieces, collision }] of byKey) {
      const mesh = key === "sphere" && pieces.length > IMPOSTOR_SPHERES
        ? new SphereImpostors(pieces.length)
        : new THREE.InstancedMesh(geometry, new THREE.MeshLambertMaterial(), pieces.length);
      if (mesh.isInstancedMesh) mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
      mesh.frustumCulled = false;
      pieces.forEach((piece, i) => {
        mesh.setColorAt(i, bodyColor(this.bodies[piece.body], piece.body));
        mesh.setMatrixAt(i, new THREE.Matrix4().makeScale(0, 0, 0)); // hidden until a pose arrives
      });
      this.worldObjects.add(mesh);
      this.groups.push({ mesh, pieces, collision });
    }
    const hasPlane = world.bodies.some((body) => planeOf(body));
    this.hasVisuals = this.visuals.length > 0;
    this.sun.castShadow = this.hasVisuals;
    if (this.hasVisuals && !hasPlane) this.addGround();
    const selected = rebuild ? this.selected : -1;
    this.joints.setWorld(world);
    this.joints.setSubdued(this.hasVisuals && selected < 0);
    this.applyCollisionToggle();
    this.selected = -1;
    this.frameDrawn = null;
    if (selected >= 0) this.setSelected(selected);
  }

  // The ground under robots in a world without a plane: a patch at z = 0
  // with a 1 m grid, that takes their shadows (no body: not picked).
  addGround() {
    const ground = new THREE.Group();
    const surface = new THREE.Mesh(new THREE.PlaneGeometry(400, 400), new THREE.MeshStandardMaterial({ color: 0x3b4252,
      roughness: 1, metalness: 0, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 }));
    surface.receiveShadow = true;
    const grid = cellGrid(40, 40, 0x6b7385, 0x4c566a);
    grid.position.z = 0.001;
    ground.add(surface, grid);
    this.worldObjects.add(ground);
  }

  // Visuals, or collision shapes instead (the "collision" toggle).
  setShowCollision(on) {
    this.showCollision = on;
    this.applyCollisionToggle();
    this.frameDrawn = null;
  }

  applyCollisionToggle() {
    for (const group of this.groups) if (group.collision) group.mesh.visible = this.showCollision;
    for (const { object } of this.visuals) object.userData.hidden = this.showCollision;
  }

  // The sun's shadow camera around the drawn bodies (once a world's poses are
  // known): a box a little larger than theirs, so that the shadow map's
  // texels are spent where the robots are.
  fitShadows() {
    const box = this.bodiesBox(this.visuals.map((v) => v.body));
    if (!box) return;
    const centre = box.getCenter(new THREE.Vector3());
    const radius = Math.max(0.5, box.getSize(new THREE.Vector3()).length() * 0.75);
    const direction = new THREE.Vector3(5, -3, 10).normalize();
    this.sun.target.position.copy(centre);
    this.sun.position.copy(centre).addScaledVector(direction, 4 * radius);
    const camera = this.sun.shadow.camera;
    camera.left = camera.bottom = -1.5 * radius;
    camera.right = camera.top = 1.5 * radius;
    camera.near = 0.1 * radius;
    camera.far = 8 * radius;
    camera.updateProjectionMatrix();
    this.sun.target.updateMatrixWorld();
    this.shadowsFitted = true;
  }

  addPlane(index, { point, normal }) {
    const group = new THREE.Group();
    // A finite patch of the half-space's surface, with a 1 m grid near the origin.
    const surface = new THREE.Mesh(new THREE.PlaneGeometry(400, 400), new THREE.MeshLambertMaterial({ color: 0x3b4252,
      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 })); // behind its grid lines
    surface.receiveShadow = true;
    const grid = cellGrid(40, 40, 0x6b7385, 0x4c566a);
    grid.position.z = 0.001;
    group.add(surface, grid);
    const local = new THREE.Matrix4().compose(point,
      new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 0, 1), normal), this.unitScale);
    group.matrixAutoUpdate = false;
    surface.userData.body = index;
    this.worldObjects.add(group);
    this.planes.push({ body: index, object: group, local });
  }

  setFrame(frame) {
    this.frame = frame;
  }

  // The pose of body i in the newest frame as a Matrix4 (into `out`).
  poseMatrix(i, out) {
    const p = this.frame.poses;
    const o = 7 * i;
    this.tmpPosition.set(p[o], p[o + 1], p[o + 2]);
    this.tmpQuaternion.set(p[o + 4], p[o + 5], p[o + 6], p[o + 3]).normalize();
    return out.compose(this.tmpPosition, this.tmpQuaternion, this.unitScale);
  }

  bodyPosition(i) {
    if (!this.frame || i < 0 || i >= this.frame.numBodies) return null;
    const p = this.frame.poses;
    return new THREE.Vector3(p[7 * i], p[7 * i + 1], p[7 * i + 2]);
  }

  frameMatchesWorld() {
    return this.frame && this.frame.revision === this.revision && this.frame.numBodies === this.bodies.length;
  }

  updatePoses() {
    if (this.visualsPending.failedBodies.size > 0) {
      for (const body of this.visualsPending.failedBodies) this.noVisuals.add(body);
      const camera = this.camera.position.clone();
      this.setWorld(this.world, true);
      this.camera.position.copy(camera);
    }
    const frame = this.frame;
    if (!this.frameMatchesWorld() || frame === this.frameDrawn) return false;
    const pose = this.tmpPose;
    for (const group of this.groups) {
      const { mesh, pieces } = group;
      for (let i = 0; i < pieces.length; i++) {
        this.poseMatrix(pieces[i].body, pose);
        mesh.setMatrixAt(i, this.tmpMatrix.multiplyMatrices(pose, pieces[i].local));
      }
      if (mesh.isInstancedMesh) mesh.instanceMatrix.needsUpdate = true;
      else mesh.posesChanged();
    }
    for (const plane of this.planes) {
      plane.object.matrix.multiplyMatrices(this.poseMatrix(plane.body, pose), plane.local);
    }
    for (const { body, object } of this.visuals) {
      this.poseMatrix(body, object.matrix);
      object.matrixWorldNeedsUpdate = true;
      object.visible = !object.userData.hidden;
    }
    if (this.hasVisuals && !this.shadowsFitted) this.fitShadows();
    this.updateContacts();
    this.joints.update(frame);
    this.frameDrawn = frame;
    return true;
  }

  updateContacts() {
    const visible = this.showContacts && this.frame;
    this.contactPoints.visible = this.contactNormals.visible = !!visible;
    if (!visible) return;
    const c = this.frame.contacts;
    const n = Math.min(this.frame.numContacts, MAX_CONTACTS);
    const pts = this.contactPoints.geometry.attributes.position;
    const lines = this.contactNormals.geometry.attributes.position;
    for (let i = 0; i < n; i++) {
      const o = 7 * i;
      pts.array.set([c[o], c[o + 1], c[o + 2]], 3 * i);
      lines.array.set([c[o], c[o + 1], c[o + 2],
        c[o] + NORMAL_LENGTH * c[o + 3], c[o + 1] + NORMAL_LENGTH * c[o + 4], c[o + 2] + NORMAL_LENGTH * c[o + 5]], 6 * i);
    }
    pts.needsUpdate = lines.needsUpdate = true;
    this.contactPoints.geometry.setDrawRange(0, n);
    this.contactNormals.geometry.setDrawRange(0, 2 * n);
  }

  setSelected(index) {
    const previous = this.selected;
    this.selected = index;
    for (const group of this.groups) {
      group.pieces.forEach((piece, i) => {
        if (piece.body === index) group.mesh.setColorAt(i, SELECTED);
        else if (piece.body === previous) group.mesh.setColorAt(i, bodyColor(this.bodies[piece.body], piece.body));
      });
      if (group.mesh.instanceColor) group.mesh.instanceColor.needsUpdate = true;
      if (group.mesh.colorsChanged) group.mesh.colorsChanged();
    }
    for (const { body, object } of this.visuals) {
      if (body === index) tintVisuals(object, true);
      else if (body === previous) tintVisuals(object, false);
    }
    // Joint markers come forward while a body is selected (their axes
    // lengthened: drawn again, even paused).
    this.joints.setSubdued(this.hasVisuals && index < 0);
    this.frameDrawn = null;
  }

  // The body under a point of the canvas (CSS pixels), with the world point hit.
  pick(x, y, includeStatic = true) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((x - rect.left) / rect.width) * 2 - 1, -((y - rect.top) / rect.height) * 2 + 1);
    this.raycaster.setFromCamera(ndc, this.camera);
    const hits = this.raycaster.intersectObjects(this.worldObjects.children, true);
    for (const hit of hits) {
      let body = -1;
      if (hit.instanceId !== undefined) {
        const group = this.groups.find((g) => g.mesh === hit.object);
        if (group && hit.instanceId !== undefined) body = group.pieces[hit.instanceId].body;
      } else if (hit.object.userData.body !== undefined) {
        body = hit.object.userData.body;
      }
      if (body < 0) continue;
      if (!includeStatic && this.bodies[body].is_static) continue;
      return { body, point: hit.point.clone() };
    }
    return null;
  }

  // Where a world point is on screen (CSS pixels), for tests and tooltips.
  screenPoint(world) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const v = world.clone().project(this.camera);
    return { x: rect.left + (v.x + 1) / 2 * rect.width, y: rect.top + (1 - v.y) / 2 * rect.height };
  }

  // A world point under the cursor on the plane through `through` facing the camera.
  pointOnViewPlane(x, y, through) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((x - rect.left) / rect.width) * 2 - 1, -((y - rect.top) / rect.height) * 2 + 1);
    this.raycaster.setFromCamera(ndc, this.camera);
    const normal = this.camera.getWorldDirection(new THREE.Vector3());
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(normal, through);
    return this.raycaster.ray.intersectPlane(plane, new THREE.Vector3());
  }

  showArrow(from, to, color) {
    const d = to.clone().sub(from);
    const length = d.length();
    if (length < 1e-6) {
      this.arrow.visible = false;
      return;
    }
    this.arrow.position.copy(from);
    this.arrow.setDirection(d.normalize());
    this.arrow.setLength(length, Math.min(0.2, length * 0.3), Math.min(0.1, length * 0.15));
    this.arrow.setColor(color);
    this.arrow.visible = true;
  }

  hideArrow() {
    this.arrow.visible = false;
  }

  render() {
    if (this.follow && this.selected >= 0) {
      const p = this.bodyPosition(this.selected);
      if (p) {
        const shift = p.clone().sub(this.controls.target);
        this.controls.target.add(shift);
        this.camera.position.add(shift);
      }
    }
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
  }

  // The world-frame box around the bodies `indices` at their drawn poses
  // (planes, being infinite, left out), or null when there is none.
  bodiesBox(indices) {
    if (!this.frameMatchesWorld()) return null;
    const box = new THREE.Box3();
    const pose = new THREE.Matrix4();
    for (const i of indices) {
      const local = this.bodyBounds[i];
      if (local) box.union(local.clone().applyMatrix4(this.poseMatrix(i, pose)));
    }
    return box.isEmpty() ? null : box;
  }

  // Points the camera at the centre of `box` from the direction it looks now,
  // at the distance where the box's eight corners fill FRAME_FILL of the view.
  // For a corner at (x, y, z) from the centre in the camera's axes (right, up,
  // back) and the camera at distance D, it is inside when |x| <= (D - z) tanH
  // and |y| <= (D - z) tanV (tanV = tan(fov/2), tanH = aspect tanV): so D is
  // the largest z + |x|/tanH and z + |y|/tanV.
  fitBox(box) {
    const centre = box.getCenter(new THREE.Vector3());
    const back = this.camera.position.clone().sub(this.controls.target);
    if (back.lengthSq() < 1e-12) back.copy(DEFAULT_VIEW);
    back.normalize();
    this.camera.position.copy(centre).add(back);
    this.camera.lookAt(centre);
    this.camera.updateMatrixWorld();
    const right = new THREE.Vector3().setFromMatrixColumn(this.camera.matrixWorld, 0);
    const up = new THREE.Vector3().setFromMatrixColumn(this.camera.matrixWorld, 1);
    const tanV = Math.tan(THREE.MathUtils.degToRad(this.camera.fov) / 2) * FRAME_FILL;
    const tanH = tanV * this.camera.aspect;
    let distance = 0;
    let farthest = 0;
    const corner = new THREE.Vector3();
    for (let k = 0; k < 8; k++) {
      corner.set(k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y, k & 4 ? box.max.z : box.min.z).sub(centre);
      const z = corner.dot(back);
      // In front of the near plane too, for a body smaller than it.
      distance = Math.max(distance, z + Math.abs(corner.dot(right)) / tanH, z + Math.abs(corner.dot(up)) / tanV,
        z + 2 * this.camera.near);
      farthest = Math.max(farthest, corner.length());
    }
    if (distance + farthest > this.camera.far) {
      this.camera.far = 2 * (distance + farthest);
      this.camera.updateProjectionMatrix();
    }
    this.controls.target.copy(centre);
    this.camera.position.copy(centre).addScaledVector(back, distance);
    this.controls.update();
  }

  // Frames every body but the planes (or those of `indices`); false when there
  // is none (or no pose yet).
  frameAll(indices = this.bodies.keys()) {
    const box = this.bodiesBox(indices);
    if (box) this.fitBox(box);
    return !!box;
  }

  // The bodies but the planes and the strays: those more than STRAY_DISTANCE
  // times the median distance from the median of the bodies' centres (per
  // axis). Framed, one stray (the default world's box dropped from 40 m, or
  // its roller rolled away a minute ago) would shrink all the others to specks.
  gatheredBodies() {
    const indices = [...this.bodies.keys()].filter((i) => this.bodyBounds[i]);
    if (indices.length < 3 || !this.frameMatchesWorld()) return indices;
    const median = (values) => {
      const sorted = Float64Array.from(values).sort();
      const m = sorted.length >> 1;
      return sorted.length % 2 ? sorted[m] : (sorted[m - 1] + sorted[m]) / 2;
    };
    const centres = indices.map((i) => this.bodyPosition(i));
    const middle = new THREE.Vector3(median(centres.map((c) => c.x)), median(centres.map((c) => c.y)),
      median(centres.map((c) => c.z)));
    const distances = centres.map((c) => c.distanceTo(middle));
    const reach = STRAY_DISTANCE * median(distances);
    return indices.filter((_, k) => distances[k] <= reach);
  }

  // Frames body `index`; false for a plane, or before its pose is known.
  frameBody(index) {
    const box = index >= 0 ? this.bodiesBox([index]) : null;
    if (box) this.fitBox(box);
    return !!box;
  }

  focusOn(index) {
    const p = this.bodyPosition(index);
    if (!p) return;
    const size = bodySize(this.bodies[index]);
    const offset = this.camera.position.clone().sub(this.controls.target).setLength(Math.max(2, 8 * size));
    this.controls.target.copy(p);
    this.camera.position.copy(p).add(offset);
  }
}
