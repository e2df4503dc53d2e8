// Reads the bridge's binary frames (layouts: clients/web/rbview_bridge/frames.py):
// a step's state, and in a world with joints the same step's joints just before it.
const MAGIC = 0x31564252;
const KIND_STATE = 1;
const KIND_JOINTS = 2;
const HEADER_BYTES = 64;
const JOINTS_HEADER_BYTES = 48;
const JOINT_FLOATS = 9;

function parseStateFrame(buffer, view) {
  if (buffer.byteLength < HEADER_BYTES) return null;
  const numBodies = view.getUint32(40, true);
  const numContacts = view.getUint32(44, true);
  const expected = HEADER_BYTES + 4 * (numBodies * 13 + numContacts * 7);
  if (buffer.byteLength !== expected) return null;
  let at = HEADER_BYTES;
  const poses = new Float32Array(buffer, at, numBodies * 7);
  at += poses.byteLength;
  const velocities = new Float32Array(buffer, at, numBodies * 6);
  at += velocities.byteLength;
  const contacts = new Float32Array(buffer, at, numContacts * 7);
  return {
    kind: "state",
    step: view.getFloat64(8, true),
    simTime: view.getFloat64(16, true),
    utime: view.getFloat64(24, true),
    revision: view.getFloat64(32, true),
    numBodies,
    numContacts,
    totalContacts: view.getUint32(48, true),
    atRest: view.getUint32(52, true),
    contactsStep: view.getFloat64(56, true),
    poses,
    velocities,
    contacts,
    receivedAt: performance.timeOrigin + performance.now(),
  };
}

function parseJointsFrame(buffer, view) {
  if (buffer.byteLength < JOINTS_HEADER_BYTES) return null;
  const numJoints = view.getUint32(40, true);
  if (buffer.byteLength !== JOINTS_HEADER_BYTES + numJoints * (4 * JOINT_FLOATS + 2)) return null;
  const numbers = new Float32Array(buffer, JOINTS_HEADER_BYTES, numJoints * JOINT_FLOATS);
  const atLimit = new Int8Array(buffer, JOINTS_HEADER_BYTES + numbers.byteLength, numJoints);
  const active = new Uint8Array(buffer, JOINTS_HEADER_BYTES + numbers.byteLength + numJoints, numJoints);
  return {
    kind: "joints",
    step: view.getFloat64(8, true),
    simTime: view.getFloat64(16, true),
    utime: view.getFloat64(24, true),
    revision: view.getFloat64(32, true),
    numJoints,
    // Per joint: position, rate, effort, force x y z, torque x y z.
    numbers,
    atLimit,
    active,
  };
}

// A frame of either kind ({kind: "state" | "joints", ...}), or null if it is not one.
export function parseFrame(buffer) {
  if (buffer.byteLength < 8) return null;
  const view = new DataView(buffer);
  if (view.getUint32(0, true) !== MAGIC) return null;
  const kind = view.getUint32(4, true);
  if (kind === KIND_STATE) return parseStateFrame(buffer, view);
  if (kind === KIND_JOINTS) return parseJointsFrame(buffer, view);
  return null;
}
