// Reads the bridge's binary state frame (layout: clients/web/rbview_bridge/frames.py).
const MAGIC = 0x31564252;
const HEADER_BYTES = 64;

export function parseStateFrame(buffer) {
  if (buffer.byteLength < HEADER_BYTES) return null;
  const view = new DataView(buffer);
  if (view.getUint32(0, true) !== MAGIC || view.getUint32(4, true) !== 1) return null;
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
