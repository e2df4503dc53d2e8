// The WebSocket to the rbview bridge: JSON text messages (world, status,
// acks, replay position) and binary frames (a step's state, after its joints'
// in a world with joints). After each state frame the page answers
// {"type": "ready"}, which is what lets the bridge send the next (newest) one:
// a slow page gets fewer frames, never older ones.
import { parseFrame } from "./frame.js";

export class Connection {
  constructor(url, handlers) {
    this.url = url;
    this.handlers = handlers; // {hello, world, status, joints, state, replay, scans, closed}
    this.nextId = 1;
    this.pending = new Map(); // request id -> resolve
    this.open();
  }

  open() {
    const socket = new WebSocket(this.url);
    socket.binaryType = "arraybuffer";
    socket.onmessage = (event) => this.receive(event.data);
    socket.onclose = (event) => {
      for (const resolve of this.pending.values()) {
        resolve({ accepted: false, reason: "connection to rbview closed" });
      }
      this.pending.clear();
      this.handlers.closed(event);
      setTimeout(() => this.open(), 1000);
    };
    this.socket = socket;
  }

  receive(data) {
    if (data instanceof ArrayBuffer) {
      const frame = parseFrame(data);
      // A step's joints come just before its state, under the same "ready":
      // kept until the state is here, and both handed over together.
      if (frame && frame.kind === "joints") {
        this.jointsOfNextState = frame;
        return;
      }
      // Ready for the next one right away: drawing happens at the display's
      // pace from the newest frame held, so this only bounds what is in flight.
      this.send({ type: "ready" });
      const joints = this.jointsOfNextState;
      this.jointsOfNextState = null;
      if (!frame) return;
      if (joints && joints.step === frame.step && joints.revision === frame.revision) this.handlers.joints(joints);
      this.handlers.state(frame);
      return;
    }
    const message = JSON.parse(data);
    if (message.type === "ack") {
      const resolve = this.pending.get(message.id);
      if (resolve) {
        this.pending.delete(message.id);
        resolve(message);
      }
      return;
    }
    const handler = this.handlers[message.type];
    if (handler) handler(message);
  }

  send(message) {
    if (this.socket.readyState === WebSocket.OPEN) this.socket.send(JSON.stringify(message));
  }

  // Sends a command, wrench or replay request; resolves with its ack
  // ({accepted, reason, effective_step}).
  request(message) {
    const id = this.nextId++;
    return new Promise((resolve) => {
      if (this.socket.readyState !== WebSocket.OPEN) {
        resolve({ accepted: false, reason: "not connected to rbview" });
        return;
      }
      this.pending.set(id, resolve);
      this.send({ ...message, id });
    });
  }
}
