// The heads-up display: the server's status and what the page draws.
const $ = (id) => document.getElementById(id);

function fixed(value, digits) {
  return typeof value === "number" && Number.isFinite(value) ? value.toFixed(digits) : "–";
}

export class Hud {
  constructor() {
    this.fields = {};
    for (const id of ["connection", "sim-time", "step", "rtf", "overruns", "bodies", "asleep", "contacts",
      "paused", "fps", "latency", "selected"]) {
      this.fields[id] = $(`hud-${id}`);
    }
  }

  set(id, text) {
    const element = this.fields[id];
    if (element.textContent !== text) element.textContent = text;
  }

  connection(text) { this.set("connection", text); }

  world(world) { this.set("bodies", String(world.bodies.length)); }

  frame(frame) {
    this.set("sim-time", `${fixed(frame.simTime, 3)} s`);
    this.set("step", String(frame.step));
    // A replayed log may hold no status: count the bodies at rest instead.
    if (!this.sleepingFromStatus) this.set("asleep", String(frame.atRest));
  }

  status(status) {
    const target = status.target_rtf === 0 ? "max" : fixed(status.target_rtf, 2);
    this.set("rtf", `${fixed(status.measured_rtf, 2)} (target ${target})`);
    this.set("overruns", String(status.overruns));
    this.set("contacts", String(status.num_contacts));
    this.sleepingFromStatus = true;
    this.set("asleep", String(status.num_sleeping_bodies));
    this.set("paused", status.paused ? "paused" : "running");
  }

  replay(replay) {
    this.set("paused", replay.playing ? `replaying ${replay.speed}×` : "replay paused");
    this.set("rtf", `replay ${replay.speed}×`);
  }

  drawn(fps, statesPerSecond) {
    this.set("fps", `${fixed(fps, 0)} fps, ${fixed(statesPerSecond, 0)} states/s`);
  }

  latency(p50, p99) {
    this.set("latency", `${fixed(p50, 1)} ms p50, ${fixed(p99, 1)} ms p99`);
  }

  selected(text) { this.set("selected", text); }

  // The selected body's joints, one line each (jointLines); none: hidden.
  joints(lines) {
    const element = this.jointsElement || (this.jointsElement = $("hud-joints"));
    const text = lines.join("\n");
    if (element.textContent !== text) element.textContent = text;
    element.classList.toggle("hidden", lines.length === 0);
  }
}

function jointPosition(joint, state) {
  const unit = joint.type === "revolute" || joint.type === "spherical" ? "rad" : "m";
  if (joint.type === "fixed" || (joint.type === "spherical" && !state.position)) return "";
  return ` ${state.position >= 0 ? " " : ""}${state.position.toFixed(3)} ${unit}`;
}

// An axis joint's rate and the effort its actuators applied (what a
// robot's controller reads in robot_state_t): ", 0.120 rad/s, -41.20 N·m".
function jointMotion(type, state) {
  if (type !== "revolute" && type !== "prismatic") return "";
  const revolute = type === "revolute";
  return `, ${state.rate.toFixed(3)} ${revolute ? "rad/s" : "m/s"}, ${state.effort.toFixed(2)} ${revolute ? "N·m" : "N"}`;
}

// "name (type) position unit, rate, effort, at the lower limit" for each
// joint of a body (JointsView.jointsOfBody), as the joints frame gives them.
export function jointLines(joints) {
  return joints.map(({ name, type, state }) => {
    if (!state) return `${name} (${type})`;
    const limit = state.atLimit < 0 ? ", at lower limit" : state.atLimit > 0 ? ", at upper limit" : "";
    const inactive = state.active ? "" : ", not enforced (a body is frozen)";
    return `${name} (${type})${jointPosition({ type }, state)}${jointMotion(type, state)}${limit}${inactive}`;
  });
}
