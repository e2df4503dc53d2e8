// A body of the world message -> the pieces it is drawn with. Each piece is a
// geometry shared by every piece of the same kind and size (so the scene draws
// them as one InstancedMesh: 2000 bodies are a handful of draw calls), and a
// matrix placing it in the body frame (principal axes at the centre of mass,
// the frame of the state's pose).
//
// Frames (lcmtypes/rbsim/body_description_t.lcm): p_body = R(shape_orientation)
// p_shape + shape_position; a compound part: p_shape = R(orientation) p_part +
// position. rbsim's cylinders and capsules lie along their frame's z axis,
// three.js's along y, hence the turn about x.
import * as THREE from "three";

const Z_FROM_Y = new THREE.Matrix4().makeRotationX(Math.PI / 2);

function quaternion(q) {
  // Wire order (w, x, y, z); three.js takes (x, y, z, w).
  return new THREE.Quaternion(q[1], q[2], q[3], q[0]).normalize();
}

function placement(position, orientation) {
  return new THREE.Matrix4().compose(
    new THREE.Vector3(position[0], position[1], position[2]),
    quaternion(orientation),
    new THREE.Vector3(1, 1, 1),
  );
}

const unitGeometries = new Map();
function unitGeometry(key, make) {
  if (!unitGeometries.has(key)) unitGeometries.set(key, make());
  return unitGeometries.get(key);
}

function meshGeometry(vertices, triangles) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.Float32BufferAttribute(vertices, 3));
  geometry.setIndex(triangles);
  const flat = geometry.toNonIndexed(); // faceted: one normal per triangle
  flat.computeVertexNormals();
  return flat;
}

// Segments of the round primitives: fewer when the world is large, so that
// thousands of bodies stay within what a software renderer draws at 60 Hz.
function roundSegments(bodyCount) {
  if (bodyCount > 500) return { around: 8, along: 6 };
  if (bodyCount > 100) return { around: 16, along: 10 };
  return { around: 24, along: 16 };
}

// Pieces of one solid (a body's shape or a compound's part) in its own frame.
function solidPieces(solid, meshKey, segments) {
  const { around, along } = segments;
  const scale = new THREE.Matrix4();
  switch (solid.shape_type) {
    case "sphere": {
      const r = solid.radius;
      return [{ key: "sphere", geometry: () => unitGeometry(`sphere:${around}`, () => new THREE.SphereGeometry(1, around, along)),
        local: scale.makeScale(r, r, r) }];
    }
    case "box": {
      const h = solid.half_extents;
      return [{ key: "box", geometry: () => unitGeometry("box", () => new THREE.BoxGeometry(2, 2, 2)),
        local: scale.makeScale(h[0], h[1], h[2]) }];
    }
    case "cylinder": {
      const r = solid.radius;
      const geometry = () => unitGeometry(`cylinder:${around}`, () => new THREE.CylinderGeometry(1, 1, 2, around).applyMatrix4(Z_FROM_Y));
      return [{ key: "cylinder", geometry, local: scale.makeScale(r, r, solid.half_length) }];
    }
    case "capsule": {
      // Caps must stay round: one geometry per (radius, half length).
      const key = `capsule:${solid.radius}:${solid.half_length}:${around}`;
      const geometry = () => unitGeometry(key, () =>
        new THREE.CapsuleGeometry(solid.radius, 2 * solid.half_length, along / 2, around).applyMatrix4(Z_FROM_Y));
      return [{ key, geometry, local: scale.identity() }];
    }
    case "mesh":
    case "trimesh": { // a static surface of triangles: drawn as a mesh is
      if (solid.vertices.length < 9 || solid.triangles.length < 3) return [];
      const geometry = () => unitGeometry(meshKey, () => meshGeometry(solid.vertices, solid.triangles));
      return [{ key: meshKey, geometry, local: scale.identity() }];
    }
    default:
      return [];
  }
}

// All pieces of a body: [{key, geometry(), local: Matrix4 in the body frame}].
// Planes are not pieces (see planeOf).
export function bodyPieces(body, bodyCount) {
  const segments = roundSegments(bodyCount);
  const shapeInBody = placement(body.shape_position, body.shape_orientation);
  const solids = [];
  if (body.shape_type === "compound") {
    body.parts.forEach((part, index) => {
      const partInShape = placement(part.position, part.orientation);
      for (const piece of solidPieces(part, `mesh:${body.id}:${index}`, segments)) {
        solids.push({ ...piece, local: new THREE.Matrix4().multiplyMatrices(partInShape, piece.local) });
      }
    });
  } else {
    solids.push(...solidPieces(body, `mesh:${body.id}`, segments));
  }
  return solids.map((piece) => ({
    ...piece,
    local: new THREE.Matrix4().multiplyMatrices(shapeInBody, piece.local),
  }));
}

// The shape frame in the body frame (a robot body's link frame).
export function shapeFrame(body) {
  return placement(body.shape_position, body.shape_orientation);
}

// A plane body -> {normal, offset} in the body frame, or null.
export function planeOf(body) {
  if (body.shape_type !== "plane") return null;
  const shapeInBody = placement(body.shape_position, body.shape_orientation);
  const n = new THREE.Vector3(...body.plane_normal).normalize();
  const point = n.clone().multiplyScalar(body.plane_offset).applyMatrix4(shapeInBody);
  const normal = n.clone().transformDirection(shapeInBody);
  return { point, normal };
}

// A rough size of a body (m), for the camera when following it.
export function bodySize(body) {
  const s = body.shape_type;
  if (s === "sphere") return body.radius;
  if (s === "box") return Math.max(...body.half_extents);
  if (s === "cylinder" || s === "capsule") return body.half_length + body.radius;
  return 0.5;
}
