// Joints drawn over the bodies: a round marker at each joint's anchor, the axis
// of a revolute or prismatic joint as a short arrow (a ball joint's cone axis as
// a line), a distance joint as a line between its anchors (a zigzag for a
// spring). Everything is carried by the bodies' poses: the bridge gives each
// anchor in its body's frame and the axis in body_a's frame
// (rbview_bridge/joint_anchors.py); a world side stays where it is. The marker
// is where body_b holds the joint, or the world's anchor for a joint to the
// world (a prismatic joint's rail stays put and its body slides along it). A
// marker turns red while its joint is held at a limit (the joints frame).
//
// All joints are one Points and one LineSegments draw, drawn on top of the
// bodies (no depth test): an anchor is often inside a body (a wheel's axle).
import * as THREE from "three";
import { bodySize } from "./shapes.js";

const MARKER_PX = 10;
// Subdued (a world of robots drawn as themselves, nothing selected): smaller
// and see-through, so that the markers do not hide the links.
const SUBDUED_MARKER_PX = 6;
const SUBDUED_OPACITY = 0.35;
// and axes this much shorter: at full length (up to 1.5 m) they cross a
// 0.4 m robot link and much of the picture.
const SUBDUED_AXIS_SCALE = 0.3;
const SPRING_ZIGZAGS = 12; // corners of a spring's zigzag
const COLORS = {
  revolute: new THREE.Color(0x4dabf7), prismatic: new THREE.Color(0x51cf66), spherical: new THREE.Color(0xcc5de8),
  fixed: new THREE.Color(0xced4da), rope: new THREE.Color(0xf1f3f5), rod: new THREE.Color(0xadb5bd),
  spring: new THREE.Color(0xffd43b),
};
const AT_LIMIT = new THREE.Color(0xff4d4f);
const INACTIVE = new THREE.Color(0x495057);

const markerVertexShader = /* glsl */ `
  attribute vec3 color;
  uniform float size;
  varying vec3 vColor;
  void main() {
    gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
    gl_PointSize = size;
    vColor = color;
  }`;

// A disc with a dark rim, so that a marker reads on any body's colour.
const markerFragmentShader = /* glsl */ `
  varying vec3 vColor;
  uniform float opacity;
  void main() {
    float r = length(gl_PointCoord * 2.0 - 1.0);
    if (r > 1.0) discard;
    gl_FragColor = vec4(r > 0.7 ? vec3(0.08) : vColor, opacity);
  }`;

// How a joint is drawn: "axis" (revolute, prismatic: an arrow), "cone" (a ball
// joint with a cone limit: its axis), "link" (distance: a line between the
// anchors, "spring" a zigzag) or "point" (the marker alone).
function styleOf(joint) {
  if (joint.type === "revolute" || joint.type === "prismatic") return "axis";
  if (joint.type === "spherical") return joint.cone_angle > 0 ? "cone" : "point";
  if (joint.type === "distance") return joint.spring ? "spring" : "link";
  return "point";
}

function colorOf(joint) {
  if (joint.type === "distance") return COLORS[joint.spring ? "spring" : joint.limit_enabled ? "rope" : "rod"];
  return COLORS[joint.type] || COLORS.fixed;
}

const SEGMENTS = { axis: 3, cone: 1, link: 1, spring: SPRING_ZIGZAGS + 1, point: 0 };

export class JointsView {
  constructor(scene) {
    this.visible = true;
    this.joints = [];
    this.states = null; // the newest joints frame of this world
    this.drawnCount = 0;
    this.markers = new THREE.Points(new THREE.BufferGeometry(), new THREE.ShaderMaterial({
      vertexShader: markerVertexShader, fragmentShader: markerFragmentShader,
      uniforms: { size: { value: MARKER_PX }, opacity: { value: 1 } }, depthTest: false, depthWrite: false,
      transparent: true,
    }));
    this.lines = new THREE.LineSegments(new THREE.BufferGeometry(),
      new THREE.LineBasicMaterial({ vertexColors: true, depthTest: false, depthWrite: false, transparent: true }));
    for (const o of [this.markers, this.lines]) {
      o.frustumCulled = false;
      o.renderOrder = 10; // after the bodies
      o.visible = false; // until a world with joints
      scene.add(o);
    }
    this.markers.renderOrder = 11;
    this.tmp = { a: new THREE.Vector3(), b: new THREE.Vector3(), d: new THREE.Vector3(), side: new THREE.Vector3(),
      p: new THREE.Vector3() };
  }

  // world: the bridge's world message; only joints whose anchors the bridge
  // placed on their bodies are drawn.
  setWorld(world) {
    const index = new Map(world.bodies.map((b, i) => [b.name, i]));
    const side = (name) => (name === "world" ? -1 : index.has(name) ? index.get(name) : null);
    this.joints = [];
    let markers = 0;
    let segments = 0;
    (world.joints || []).forEach((joint, k) => {
      const a = side(joint.body_a);
      const b = side(joint.body_b);
      if (a === null || b === null || !joint.local_anchor_a || !joint.local_anchor_b || !joint.local_axis) return;
      const style = styleOf(joint);
      const size = b >= 0 ? bodySize(world.bodies[b]) : a >= 0 ? bodySize(world.bodies[a]) : 0.2;
      this.joints.push({
        index: k, name: joint.name, type: joint.type, style, a, b, color: colorOf(joint),
        localA: new THREE.Vector3(...joint.local_anchor_a), localB: new THREE.Vector3(...joint.local_anchor_b),
        axis: new THREE.Vector3(...joint.local_axis).normalize(),
        length: Math.min(1.0, Math.max(0.3, 1.5 * size)),
        firstMarker: markers, firstSegment: segments,
      });
      markers += style === "link" || style === "spring" ? 2 : 1;
      segments += SEGMENTS[style];
    });
    this.worldRevision = world.revision;
    this.worldJointCount = (world.joints || []).length;
    this.states = null;
    this.markerCount = markers;
    this.segmentCount = segments;
    const attribute = (n) => new THREE.BufferAttribute(new Float32Array(Math.max(1, n) * 3), 3)
      .setUsage(THREE.DynamicDrawUsage);
    for (const [object, vertices] of [[this.markers, markers], [this.lines, 2 * segments]]) {
      object.geometry.dispose();
      object.geometry = new THREE.BufferGeometry();
      object.geometry.setAttribute("position", attribute(vertices));
      object.geometry.setAttribute("color", attribute(vertices));
      object.geometry.setDrawRange(0, 0);
      object.visible = false; // until update: a world without joints costs no draw call
    }
    this.drawnCount = 0;
  }

  // Smaller, see-through markers and shorter, see-through axes (true), or as
  // they are drawn alone (the axes' length takes effect at the next update).
  setSubdued(subdued) {
    this.subdued = subdued;
    this.markers.material.uniforms.size.value = subdued ? SUBDUED_MARKER_PX : MARKER_PX;
    this.markers.material.uniforms.opacity.value = subdued ? SUBDUED_OPACITY : 1;
    this.lines.material.opacity = subdued ? SUBDUED_OPACITY : 1;
  }

  // The newest joints frame; kept only if it is of this world.
  setStates(frame) {
    this.states = frame.revision === this.worldRevision && frame.numJoints === this.worldJointCount ? frame : null;
  }

  // Joint k's numbers in the newest joints frame, or null.
  stateOf(k) {
    const s = this.states;
    if (!s) return null;
    const n = s.numbers;
    return { position: n[9 * k], rate: n[9 * k + 1], effort: n[9 * k + 2], atLimit: s.atLimit[k],
      active: s.active[k] !== 0, step: s.step };
  }

  // A body-frame point (or a world point for side -1) into the world, with the poses of `frame`.
  static carry(frame, body, local, out) {
    if (body < 0) return out.copy(local);
    const p = frame.poses;
    const o = 7 * body;
    JointsView.turn(p, o, local, out);
    return out.set(out.x + p[o], out.y + p[o + 1], out.z + p[o + 2]);
  }

  // v turned by the orientation of the pose at p[o..o+6] (w x y z at o+3), into out.
  static turn(p, o, v, out) {
    let w = p[o + 3], x = p[o + 4], y = p[o + 5], z = p[o + 6];
    const norm = Math.hypot(w, x, y, z) || 1;
    w /= norm; x /= norm; y /= norm; z /= norm;
    // v + 2w (u x v) + 2 u x (u x v), u = (x, y, z)
    const tx = 2 * (y * v.z - z * v.y), ty = 2 * (z * v.x - x * v.z), tz = 2 * (x * v.y - y * v.x);
    return out.set(v.x + w * tx + (y * tz - z * ty), v.y + w * ty + (z * tx - x * tz), v.z + w * tz + (x * ty - y * tx));
  }

  update(frame) {
    const shown = this.visible && this.joints.length > 0;
    this.markers.visible = this.lines.visible = shown;
    this.drawnCount = 0;
    if (!shown || !frame) return;
    const markerPositions = this.markers.geometry.attributes.position.array;
    const markerColors = this.markers.geometry.attributes.color.array;
    const linePositions = this.lines.geometry.attributes.position.array;
    const lineColors = this.lines.geometry.attributes.color.array;
    const { a, b, d, side, p } = this.tmp;
    const setMarker = (i, point, color) => {
      point.toArray(markerPositions, 3 * i);
      color.toArray(markerColors, 3 * i);
    };
    const setSegment = (i, from, to, color) => {
      from.toArray(linePositions, 6 * i);
      to.toArray(linePositions, 6 * i + 3);
      color.toArray(lineColors, 6 * i);
      color.toArray(lineColors, 6 * i + 3);
    };
    for (const j of this.joints) {
      JointsView.carry(frame, j.a, j.localA, a);
      JointsView.carry(frame, j.b, j.localB, b);
      const marker = j.a < 0 ? a : b; // a world side's anchor, else body_b's
      const state = this.stateOf(j.index);
      const markerColor = state && !state.active ? INACTIVE : state && state.atLimit !== 0 ? AT_LIMIT : j.color;
      let s = j.firstSegment;
      switch (j.style) {
        case "axis":
        case "cone": {
          if (j.a < 0) d.copy(j.axis);
          else JointsView.turn(frame.poses, 7 * j.a, j.axis, d);
          const length = this.subdued ? SUBDUED_AXIS_SCALE * j.length : j.length;
          const tip = p.copy(marker).addScaledVector(d, length);
          setSegment(s++, side.copy(marker).addScaledVector(d, j.style === "axis" ? -0.5 * length : 0), tip, j.color);
          if (j.style === "axis") {
            // An arrowhead: two strokes back from the tip, across the axis.
            const across = side.set(0, 0, 1);
            if (Math.abs(d.z) > 0.9) across.set(1, 0, 0);
            across.cross(d).normalize().multiplyScalar(0.08 * length);
            const back = d.clone().multiplyScalar(-0.2 * length).add(tip);
            setSegment(s++, tip, back.clone().add(across), j.color);
            setSegment(s++, tip, back.sub(across), j.color);
          }
          setMarker(j.firstMarker, marker, markerColor);
          break;
        }
        case "link":
          setSegment(s++, a, b, j.color);
          setMarker(j.firstMarker, a, markerColor);
          setMarker(j.firstMarker + 1, b, markerColor);
          break;
        case "spring": {
          // A zigzag across the line between the anchors.
          d.subVectors(b, a);
          const across = side.set(0, 0, 1);
          if (d.lengthSq() > 0 && Math.abs(d.clone().normalize().z) > 0.9) across.set(1, 0, 0);
          across.cross(d).normalize().multiplyScalar(0.06);
          let previous = a.clone();
          for (let i = 1; i <= SPRING_ZIGZAGS; i++) {
            const corner = a.clone().addScaledVector(d, i / (SPRING_ZIGZAGS + 1)).addScaledVector(across, i % 2 ? 1 : -1);
            setSegment(s++, previous, corner, j.color);
            previous = corner;
          }
          setSegment(s++, previous, b, j.color);
          setMarker(j.firstMarker, a, markerColor);
          setMarker(j.firstMarker + 1, b, markerColor);
          break;
        }
        default:
          setMarker(j.firstMarker, marker, markerColor);
      }
      this.drawnCount++;
    }
    for (const object of [this.markers, this.lines]) {
      object.geometry.attributes.position.needsUpdate = true;
      object.geometry.attributes.color.needsUpdate = true;
    }
    this.markers.geometry.setDrawRange(0, this.markerCount);
    this.lines.geometry.setDrawRange(0, 2 * this.segmentCount);
  }

  // The joints of body i: [{name, type, state}] (state null until a joints frame comes).
  jointsOfBody(i) {
    if (i < 0) return []; // -1 is no body here, not the world
    return this.joints.filter((j) => j.a === i || j.b === i)
      .map((j) => ({ name: j.name, type: j.type, state: this.stateOf(j.index) }));
  }

  // Where joint `name`'s marker is drawn (world), or null.
  markerOf(frame, name) {
    const j = this.joints.find((x) => x.name === name);
    if (!j || !frame) return null;
    const a = JointsView.carry(frame, j.a, j.localA, new THREE.Vector3());
    const b = JointsView.carry(frame, j.b, j.localB, new THREE.Vector3());
    return j.a < 0 ? a : b;
  }
}
