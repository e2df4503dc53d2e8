// rbview's page: connects to the bridge that served it, draws the world and
// drives the server through the bridge (every action waits for its ack).
import * as THREE from "three";
import "./style.css";
import { Connection } from "./connection.js";
import { Viewer } from "./scene.js";
import { Hud, jointLines } from "./hud.js";
import { Plots } from "./plots.js";
import { ScansView } from "./scans.js";

// The HUD's per-state text (sim time, step, at rest) is written at most this
// often: faster than 10 Hz it cannot be read, and every change costs the page a
// style, layout and paint and the compositor a raster of the panel.
const HUD_INTERVAL_MS = 100;
const PUSH_GAIN = 10; // N per kg per m of drag: a 1 m drag accelerates the body at 10 m/s^2
const PUSH_DURATION = 0.25; // s of simulated time a drag's wrench acts
const CLICK_SLOP = 4; // px: a press that moves less is a click (select), not a drag

const $ = (id) => document.getElementById(id);
const viewer = new Viewer($("view"));
const hud = new Hud();
const plots = new Plots($("plots"));
const scans = new ScansView(viewer.scene);
const message = $("message");

const state = {
  world: null, status: null, hello: null, replay: null, frame: null, joints: null,
  framesReceived: 0, rendersThisSecond: 0, statesThisSecond: 0, fps: 0, statesPerSecond: 0,
  latencies: [], drawnSteps: [],
};

function say(text, kind) {
  message.textContent = text;
  message.className = `message ${kind || ""}`;
}

async function act(what, request) {
  say(`${what}: waiting for the server…`);
  const ack = await connection.request(request);
  if (ack.accepted) say(`${what}: accepted${ack.effective_step >= 0 ? ` (from step ${ack.effective_step})` : ""}`, "accepted");
  else say(`${what}: rejected: ${ack.reason}`, "rejected");
  return ack;
}

const connection = new Connection(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws`, {
  hello(hello) {
    state.hello = hello;
    hud.connection(hello.mode === "replay" ? "replaying a log" : hello.read_only ? "live (read-only)" : "live");
    const controlsOff = hello.read_only || hello.mode === "replay";
    for (const id of ["btn-pause", "btn-resume", "btn-reset", "btn-step", "btn-rtf", "step-count", "rtf-value"]) {
      $(id).disabled = controlsOff;
    }
    if (hello.read_only) say("read-only: controls are off (rbview --read-only)");
    $("replay").classList.toggle("hidden", hello.mode !== "replay");
  },
  world(world) {
    state.world = world;
    viewer.setWorld(world);
    hud.world(world);
    selectBody(-1);
  },
  status(status) {
    state.status = status;
    hud.status(status);
  },
  joints(frame) {
    state.joints = frame;
    viewer.joints.setStates(frame);
  },
  state(frame) {
    state.frame = frame;
    state.framesReceived++;
    viewer.setFrame(frame);
    frameToHud();
    if (state.world && frame.revision === state.world.revision) {
      plots.add(frame, state.world.bodies[plots.body], state.world.gravity);
    }
  },
  scans(message) {
    scans.set(message);
    const menu = $("scan-sensor");
    const names = scans.names();
    if (menu.options.length !== names.length + 1) {
      for (const name of names) {
        if (![...menu.options].some((o) => o.value === name)) menu.add(new Option(name, name));
      }
    }
    showScanInfo();
  },
  replay(replay) {
    state.replay = replay;
    hud.replay(replay);
    const timeline = $("timeline");
    timeline.min = replay.first;
    timeline.max = replay.last;
    if (!timeline.matches(":active")) timeline.value = replay.index;
    $("btn-play").textContent = replay.playing ? "Pause" : "Play";
    $("replay-position").textContent = `step ${replay.step} (steps ${replay.first_step}…${replay.last_step}), ${replay.sim_time.toFixed(3)} s`;
  },
  closed() {
    hud.connection("disconnected (retrying)");
  },
});

// The newest frame to the HUD now if it was last written HUD_INTERVAL_MS ago,
// else once that much time has passed (so the last frame is always shown).
let hudWritten = -Infinity;
let hudTimer = 0;
function writeFrameToHud() {
  hudTimer = 0;
  hudWritten = performance.now();
  hud.frame(state.frame);
  hud.joints(jointLines(viewer.joints.jointsOfBody(viewer.selected)));
}
function frameToHud() {
  if (hudTimer) return;
  const wait = HUD_INTERVAL_MS - (performance.now() - hudWritten);
  if (wait <= 0) writeFrameToHud();
  else hudTimer = setTimeout(writeFrameToHud, wait);
}

// -- controls -----------------------------------------------------------------------------
$("btn-pause").onclick = () => act("pause", { type: "command", command: "pause" });
$("btn-resume").onclick = () => act("resume", { type: "command", command: "resume" });
$("btn-reset").onclick = () => act("reset", { type: "command", command: "reset" });
$("btn-step").onclick = () => {
  const n = Number($("step-count").value);
  if (!Number.isInteger(n)) return say("step: the number of steps must be a whole number", "rejected");
  act(`step ${n}`, { type: "command", command: "step", num_steps: n });
};
$("btn-rtf").onclick = () => {
  const f = Number($("rtf-value").value);
  if (!Number.isFinite(f)) return say("real-time factor: not a number", "rejected");
  act(`real-time factor ${f}`, { type: "command", command: "set_real_time_factor", real_time_factor: f });
};
$("toggle-contacts").onchange = (e) => { viewer.showContacts = e.target.checked; viewer.frameDrawn = null; };
function showCollision(on) {
  viewer.setShowCollision(on);
  $("toggle-collision").checked = on;
}
$("toggle-collision").onchange = (e) => showCollision(e.target.checked);
$("toggle-joints").onchange = (e) => { viewer.joints.visible = e.target.checked; viewer.frameDrawn = null; };
$("toggle-follow").onchange = (e) => {
  viewer.follow = e.target.checked;
  if (viewer.follow && viewer.selected >= 0) viewer.focusOn(viewer.selected);
};
// What the drawn scan says of itself: set with the drawing, when a sensor is
// chosen as when a scan arrives, so the two never disagree.
function showScanInfo() {
  const scan = scans.drawnScan && scans.drawnScan.name === scans.selected ? scans.drawnScan : null;
  $("scan-info").textContent = scan ? `step ${scan.step}: ${scan.returns} of ${scan.beams} beams returned` : "";
}
$("scan-sensor").onchange = (e) => { scans.select(e.target.value); showScanInfo(); };
$("toggle-plots").onchange = (e) => $("plots").classList.toggle("hidden", !e.target.checked);

// Framing only moves the camera, so it works read-only and in replay too. Its
// notes ("frame ...: why not") go once it works; a server's answer stays.
function clearFrameNote() {
  if (message.textContent.startsWith("frame ")) say("");
}
function frameAll() {
  if (!viewer.frameAll()) return say("frame all: no body to frame yet");
  // Following would pull the view straight back to the selected body.
  if (viewer.follow) {
    viewer.follow = false;
    $("toggle-follow").checked = false;
  }
  clearFrameNote();
}
function frameSelected() {
  const body = viewer.selected >= 0 && state.world ? state.world.bodies[viewer.selected] : null;
  if (!body) return say("frame selected: no body selected (click one)");
  if (!viewer.frameBody(viewer.selected)) return say(`frame selected: ${body.name} is an infinite plane`);
  clearFrameNote();
}
$("btn-frame-all").onclick = frameAll;
$("btn-frame-selected").onclick = frameSelected;
// A and F, as in Maya (frame all, frame selected); not while typing into a
// field (the step count, the real-time factor) or choosing a replay speed.
const TYPING_TARGETS = "input:not([type=checkbox]):not([type=radio]):not([type=button]):not([type=range]), select, textarea";
window.addEventListener("keydown", (event) => {
  if (event.ctrlKey || event.metaKey || event.altKey) return;
  if (event.target instanceof Element && event.target.matches(TYPING_TARGETS)) return;
  const key = event.key.toLowerCase();
  if (key === "a") frameAll();
  else if (key === "f") frameSelected();
  else if (key === "c") showCollision(!viewer.showCollision);
  else return;
  event.preventDefault();
});
$("btn-play").onclick = () => {
  const playing = state.replay && state.replay.playing;
  act(playing ? "pause replay" : "play replay", { type: "replay", action: playing ? "pause" : "play" });
};
$("replay-speed").onchange = (e) => act(`speed ${e.target.value}×`, { type: "replay", action: "speed", speed: Number(e.target.value) });
$("timeline").oninput = (e) => connection.request({ type: "replay", action: "seek", index: Number(e.target.value) });

function selectBody(index) {
  viewer.setSelected(index);
  plots.select(index);
  const body = index >= 0 && state.world ? state.world.bodies[index] : null;
  hud.selected(body ? `${body.name} (${body.shape_type}${body.is_static ? ", static" : `, ${body.mass.toFixed(3)} kg`})` : "none");
  hud.joints(jointLines(viewer.joints.jointsOfBody(index)));
  if (body && viewer.follow) viewer.focusOn(index);
}

// -- picking, hovering and pushing ----------------------------------------------------------
const canvas = viewer.renderer.domElement;
const tooltip = $("tooltip");
let press = null; // {x, y, body, local: Vector3 in the body frame, moved}

function grabPointNow(drag) {
  const pose = viewer.poseMatrix(drag.body, new THREE.Matrix4());
  return drag.local.clone().applyMatrix4(pose);
}

function canPush() {
  return state.hello && !state.hello.read_only && state.hello.mode === "live";
}

canvas.addEventListener("pointerdown", (event) => {
  if (event.button !== 0) return;
  const hit = viewer.frameMatchesWorld() ? viewer.pick(event.clientX, event.clientY, false) : null;
  press = { x: event.clientX, y: event.clientY, body: hit ? hit.body : -1, moved: false };
  if (hit && canPush()) {
    const pose = viewer.poseMatrix(hit.body, new THREE.Matrix4());
    press.local = hit.point.clone().applyMatrix4(pose.invert());
    viewer.controls.enabled = false; // this drag pushes the body, it does not orbit
  }
}, { capture: true });

canvas.addEventListener("pointermove", (event) => {
  if (press) {
    if (Math.hypot(event.clientX - press.x, event.clientY - press.y) > CLICK_SLOP) press.moved = true;
    if (press.local && press.moved) {
      const from = grabPointNow(press);
      press.to = viewer.pointOnViewPlane(event.clientX, event.clientY, from);
      if (press.to) viewer.showArrow(from, press.to, 0xff8c42);
    }
    return;
  }
  hover(event.clientX, event.clientY);
});

window.addEventListener("pointerup", async (event) => {
  if (!press) return;
  const drag = press;
  press = null;
  viewer.controls.enabled = true;
  if (!drag.moved) {
    if (event.target === canvas) selectBody(drag.body);
    return;
  }
  if (!drag.local || !drag.to) return;
  const body = state.world.bodies[drag.body];
  const from = grabPointNow(drag);
  const force = drag.to.clone().sub(from).multiplyScalar(PUSH_GAIN * body.mass);
  viewer.showArrow(from, drag.to, 0xff5533);
  const ack = await act(`push ${body.name} with ${force.length().toFixed(1)} N for ${PUSH_DURATION} s`, {
    type: "wrench", body: body.name, force: force.toArray(), point: from.toArray(), duration: PUSH_DURATION,
  });
  viewer.showArrow(from, drag.to, ack.accepted ? 0x51cf66 : 0xff3333);
  setTimeout(() => viewer.hideArrow(), ack.accepted ? PUSH_DURATION * 1000 + 300 : 1500);
});

let lastHover = 0;
function hover(x, y) {
  const now = performance.now();
  if (now - lastHover < 50) return;
  lastHover = now;
  const hit = viewer.frameMatchesWorld() ? viewer.pick(x, y) : null;
  if (!hit) {
    tooltip.classList.add("hidden");
    return;
  }
  // The body's name, and its joints' positions and limits (one line each).
  tooltip.textContent = [state.world.bodies[hit.body].name, ...jointLines(viewer.joints.jointsOfBody(hit.body))].join("\n");
  tooltip.style.left = `${x + 12}px`;
  tooltip.style.top = `${y + 12}px`;
  tooltip.classList.remove("hidden");
}

// -- drawing ----------------------------------------------------------------------------------
const MAX_LATENCIES = 10000;
let secondStarted = performance.now();
function animate() {
  requestAnimationFrame(animate);
  const fresh = viewer.updatePoses();
  // The first view frames the bodies, strays left out (once, at the first
  // drawn frame, even of a world with none yet: after that the camera is the user's).
  if (fresh && !state.framedAtStart) {
    viewer.frameAll(viewer.gatheredBodies());
    state.framedAtStart = true;
  }
  viewer.render();
  state.rendersThisSecond++;
  state.renders = (state.renders || 0) + 1;
  if (fresh) state.statesThisSecond++;
  if (fresh && state.hello && state.hello.mode === "live") {
    // From rbserver publishing the step to it being drawn (same host clock).
    const latency = performance.timeOrigin + performance.now() - viewer.frameDrawn.utime / 1000;
    state.latencies.push(latency);
    if (state.latencies.length > MAX_LATENCIES) state.latencies.splice(0, MAX_LATENCIES / 2);
    state.drawnSteps.push(viewer.frameDrawn.step);
    if (state.drawnSteps.length > 1000) state.drawnSteps.splice(0, 500);
  }
  plots.draw();
  const now = performance.now();
  if (now - secondStarted >= 1000) {
    state.fps = (1000 * state.rendersThisSecond) / (now - secondStarted);
    state.statesPerSecond = (1000 * state.statesThisSecond) / (now - secondStarted);
    state.rendersThisSecond = state.statesThisSecond = 0;
    secondStarted = now;
    hud.drawn(state.fps, state.statesPerSecond);
    const recent = state.latencies.slice(-120).sort((a, b) => a - b);
    if (recent.length) hud.latency(recent[Math.floor(recent.length / 2)], recent[Math.floor(recent.length * 0.99)]);
  }
}
requestAnimationFrame(animate);

// For the browser tests and the benchmark: read-only views of what is drawn.
window.rbview = {
  state,
  viewer,
  scans,
  bodyIndex: (name) => (state.world ? state.world.bodies.findIndex((b) => b.name === name) : -1),
  screenOf(name) {
    const i = this.bodyIndex(name);
    const p = viewer.bodyPosition(i);
    return p ? viewer.screenPoint(p) : null;
  },
  // How many joints are drawn now (0 with the joints toggle off).
  jointsDrawn: () => viewer.joints.drawnCount,
  // Visual meshes still being fetched, and those that failed (visuals.js).
  visualsPending: () => viewer.visualsPending.count,
  visualsFailed: () => [...viewer.visualsPending.failed],
  visualsDrawn: () => viewer.visuals.length,
  // Visual meshes drawn, by file kind: {stl, obj, dae} (those not fetched yet or failed are not).
  visualMeshesDrawn: () => ({ ...viewer.visualsPending.drawn }),
  // The world-axis boxes around body `name`'s drawn visuals and around its
  // collision shape, as {min, max} arrays (the visual meshes and the collision
  // meshes of a URDF link are modelled in the same frame: their boxes agree).
  visualAndCollisionBoxes(name) {
    const i = this.bodyIndex(name);
    const drawn = viewer.visuals.find((v) => v.body === i);
    if (!drawn || !viewer.frame) return null;
    drawn.object.updateMatrixWorld(true);
    const visual = new THREE.Box3().setFromObject(drawn.object, true);
    // Around the collision pieces' vertices (bodyBounds, a box around boxes
    // turned by the shape frame, would be larger).
    const pose = viewer.poseMatrix(i, new THREE.Matrix4());
    const collision = new THREE.Box3();
    const toWorld = new THREE.Matrix4();
    const point = new THREE.Vector3();
    for (const { mesh, pieces, collision: drawnInstead } of viewer.groups) {
      if (!drawnInstead || !mesh.isInstancedMesh) continue;
      const positions = mesh.geometry.getAttribute("position");
      for (const piece of pieces) {
        if (piece.body !== i) continue;
        toWorld.multiplyMatrices(pose, piece.local);
        for (let k = 0; k < positions.count; k++) collision.expandByPoint(point.fromBufferAttribute(positions, k).applyMatrix4(toWorld));
      }
    }
    if (collision.isEmpty()) return null;
    const plain = (box) => ({ min: box.min.toArray(), max: box.max.toArray() });
    return { visual: plain(visual), collision: plain(collision) };
  },
  // Where joint `name`'s marker is drawn (world), or null.
  jointMarker(name) {
    const p = viewer.frameDrawn ? viewer.joints.markerOf(viewer.frameDrawn, name) : null;
    return p ? p.toArray() : null;
  },
  drawnPosition(name) {
    const p = viewer.frameDrawn ? viewer.bodyPosition(this.bodyIndex(name)) : null;
    return p ? p.toArray() : null;
  },
  // The rectangle (CSS pixels) that the box around the bodies `names`, or
  // around every body but the planes, projects to: {left, top, right, bottom}.
  screenRect(...names) {
    const box = viewer.bodiesBox(names.length ? names.map((n) => this.bodyIndex(n)) : viewer.bodies.keys());
    if (!box) return null;
    const rect = { left: Infinity, top: Infinity, right: -Infinity, bottom: -Infinity };
    for (let k = 0; k < 8; k++) {
      const p = viewer.screenPoint(new THREE.Vector3(k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y,
        k & 4 ? box.max.z : box.min.z));
      rect.left = Math.min(rect.left, p.x);
      rect.right = Math.max(rect.right, p.x);
      rect.top = Math.min(rect.top, p.y);
      rect.bottom = Math.max(rect.bottom, p.y);
    }
    return rect;
  },
  camera: () => ({ target: viewer.controls.target.toArray(), position: viewer.camera.position.toArray() }),
  lookAt(target, from) {
    viewer.controls.target.set(...target);
    viewer.camera.position.set(...from);
    viewer.controls.update();
  },
};
