// rbview's joints, in Debian's headless chromium: rbserver live on
// config/worlds/joints.yaml (nine joints: hinges with a limit, a motor and a
// servo, a double pendulum, a slider at its lower limit, a weld, a rope, a ball
// joint with a cone), then an rbserver --record of the same world replayed.
// Every joint is drawn at its anchor and carried by its bodies; selecting or
// hovering a jointed body shows its joints' positions and limits.
// Screenshots: BUILD/tests/web/artifacts/joints-*.png.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import path from "node:path";
import { fileURLToPath } from "node:url";
import {
  repo, build, artifacts, startProcess, rbview, launchBrowser, openPage, screenshot, sleep, stopAll, logs, runPython,
} from "./browser_support.mjs";

const world = path.join(repo, "config", "worlds", "joints.yaml");
const rbserverPath = path.join(build, "server", "daemon", "rbserver");
const record = path.join(artifacts, "..", "joints-session.lcmlog");
const JOINTS = 11;
// float32 poses, and anchors placed from a state up to half a state period
// away from the description's step (rbview_bridge/joint_anchors.py).
const CLOSE = 2e-3; // m

let browser, page;

before(async () => {
  // The record first: one rbserver on the bus at a time.
  const recorder = startProcess("rbserver", rbserverPath,
    ["--config", world, "--real-time-factor", "0", "--duration", "1", "--record", record, "--log-level", "info"]);
  const code = await new Promise((resolve) => recorder.on("exit", resolve));
  assert.equal(code, 0, `rbserver --record exited with ${code}\n${logs()}`);
  startProcess("rbserver", rbserverPath, ["--config", world, "--log-level", "info"]);
  browser = await launchBrowser();
  page = await openPage(browser, await rbview());
});

after(async () => {
  if (browser) await browser.close();
  stopAll();
});

function noConsoleErrors(p = page) {
  assert.deepEqual(p.errors, [], `console errors:\n${p.errors.join("\n")}\n${logs()}`);
}

const distance = (u, v) => Math.hypot(u[0] - v[0], u[1] - v[1], u[2] - v[2]);

// What is drawn now, all of one frame: every joint's anchors {a, b} (world,
// m) and every body's position.
function drawn(p) {
  return p.evaluate(() => {
    const view = rbview.viewer.joints;
    const frame = rbview.viewer.frameDrawn;
    const carry = (body, local) => view.constructor.carry(frame, body, local, local.clone()).toArray();
    const joints = Object.fromEntries(view.joints.map((j) => [j.name, { a: carry(j.a, j.localA), b: carry(j.b, j.localB) }]));
    const bodies = Object.fromEntries(rbview.state.world.bodies.map((b, i) => [b.name,
      Array.from(frame.poses.subarray(7 * i, 7 * i + 3))]));
    return { joints, bodies, marker: rbview.jointMarker("lift") };
  });
}

function lookAtEverything(p) {
  return p.evaluate(() => rbview.lookAt([-0.9, -0.6, 1.2], [1.2, -8.4, 4.6]));
}

test("the page loads with no console error and draws every joint of the world", async () => {
  await page.waitForFunction((n) => rbview.state.world.joints.length === n && rbview.jointsDrawn() === n
    && rbview.state.joints, JOINTS, { timeout: 20000 });
  const counts = await page.evaluate(() => ({
    world: rbview.state.world.joints.length,
    drawn: rbview.jointsDrawn(),
    states: rbview.state.joints.numJoints,
    markers: rbview.viewer.joints.markers.geometry.drawRange.count,
  }));
  assert.deepEqual(counts, { world: JOINTS, drawn: JOINTS, states: JOINTS, markers: JOINTS + 1 },
    "one marker per joint, two for the rope");
  await lookAtEverything(page);
  await sleep(500);
  await screenshot(page, "joints-live");
  noConsoleErrors();
});

test("each joint is drawn at its anchor and carried by its bodies", async () => {
  // A second of motion: the pendulum and the lamp swing, the servo turns, the door closes.
  await sleep(1000);
  const { joints, bodies, marker } = await drawn(page);
  for (const name of ["door_hinge", "shoulder", "elbow", "axle", "weld", "servo", "hip"]) {
    const { a, b } = joints[name];
    assert.ok(distance(a, b) < CLOSE, `${name}: drawn anchors ${a} and ${b} apart`);
  }
  // The elbow is the upper arm's centre, and half a metre from the forearm's.
  const elbow = joints.elbow.b;
  assert.ok(distance(elbow, bodies.upper_arm) < CLOSE, `elbow drawn at ${elbow}, the upper arm at ${bodies.upper_arm}`);
  assert.ok(Math.abs(distance(elbow, bodies.forearm) - 0.5) < CLOSE);
  // The rope: from its hook in the world to the lamp's centre, wherever the lamp is.
  const rope = joints.lamp_rope;
  assert.ok(distance(rope.a, [3, -3, 3]) < 1e-6, `rope hook drawn at ${rope.a}`);
  assert.ok(distance(rope.b, bodies.lamp) < CLOSE, `rope end drawn at ${rope.b}, the lamp at ${bodies.lamp}`);
  // The slider's rail stays at the world anchor; the carriage's anchor slides on it.
  const lift = joints.lift;
  assert.ok(distance(lift.a, [-3, 0, 1.5]) < 1e-6);
  assert.ok(Math.hypot(lift.b[0] + 3, lift.b[1]) < CLOSE && Math.abs(lift.b[2] - bodies.carriage[2]) < CLOSE);
  assert.deepEqual(marker, lift.a);
  noConsoleErrors();
});

test("the joints' states reach the page: positions, limits, selection and hover", async () => {
  const stateOf = (name) => page.evaluate((n) => {
    const view = rbview.viewer.joints;
    const j = view.joints.find((x) => x.name === n);
    return view.stateOf(j.index);
  }, name);
  // The servo's drive holds it at 0.8 rad; the carriage rests on the lift's lower limit.
  await page.waitForFunction(() => {
    const view = rbview.viewer.joints;
    const s = (n) => view.stateOf(view.joints.find((x) => x.name === n).index);
    return Math.abs(s("servo").position - 0.8) < 0.02 && s("lift").atLimit === -1;
  }, null, { timeout: 20000 });
  const lift = await stateOf("lift");
  assert.ok(Math.abs(lift.position + 0.5) < 1e-3, `lift at ${lift.position} m`);
  // The page holds the joints of the step it holds (they come just before its state).
  for (let i = 0; i < 20; i++) {
    const steps = await page.evaluate(() => [rbview.state.joints.step, rbview.state.frame.step]);
    assert.equal(steps[0], steps[1]);
    await sleep(20);
  }

  await page.evaluate(() => {
    const p = rbview.drawnPosition("carriage");
    rbview.lookAt(p, [p[0] + 0.5, p[1] - 3, p[2] + 1]);
  });
  await sleep(300);
  // Under load the page may draw the new view a few frames late, so a
  // click computed from the last frame can miss: click where the body is
  // after two drawn frames, and again if nothing was selected.
  for (let attempt = 0; ; attempt++) {
    await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
    const carriage = await page.evaluate(() => rbview.screenOf("carriage"));
    await page.mouse.click(carriage.x, carriage.y);
    const selected = await page.waitForFunction(
      () => document.getElementById("hud-selected").textContent.startsWith("carriage ("), null, { timeout: 3000 })
      .then(() => true, () => false);
    if (selected) break;
    if (attempt === 2)
      assert.fail(`clicking the carriage selected '${await page.locator("#hud-selected").textContent()}'`);
  }
  await page.waitForFunction(() => /^lift \(prismatic\) -0\.500 m, -?0\.000 m\/s, -?\d+\.\d\d N, at lower limit$/
    .test(document.getElementById("hud-joints").textContent), null, { timeout: 20000 });
  assert.match(await page.locator("#hud-selected").textContent(), /^carriage \(box/);
  await screenshot(page, "joints-selected");

  await lookAtEverything(page);
  await sleep(300);
  const door = await page.evaluate(() => rbview.screenOf("door"));
  await page.mouse.move(door.x, door.y);
  await page.waitForFunction(() => document.getElementById("tooltip").textContent.startsWith("door\ndoor_hinge (revolute) "),
    null, { timeout: 20000 });
  noConsoleErrors();
});

test("the joints toggle hides and shows them", async () => {
  await page.uncheck("#toggle-joints");
  await page.waitForFunction(() => rbview.jointsDrawn() === 0 && !rbview.viewer.joints.markers.visible);
  await page.check("#toggle-joints");
  await page.waitForFunction((n) => rbview.jointsDrawn() === n && rbview.viewer.joints.markers.visible, JOINTS);
  noConsoleErrors();
});

test("joints spawned while the world runs are drawn where they hold their bodies", async () => {
  // A SPAWN's description falls between two published states (a new revision):
  // the bridge places its anchors from the first state of it, carried back.
  const revision = await page.evaluate(() => rbview.state.world.revision);
  const spawn = await runPython("spawn_world_part.py",
    [path.join(path.dirname(fileURLToPath(import.meta.url)), "worlds", "bob_on_a_rod.yaml")]);
  const { code, stdout } = await spawn.done;
  assert.equal(code, 0, `SPAWN refused: ${stdout}`);
  await page.waitForFunction(({ r, n }) => rbview.state.world.revision > r && rbview.jointsDrawn() === n,
    { r: revision, n: JOINTS + 2 },
    { timeout: 10000 });
  await sleep(700);
  const { joints, bodies } = await drawn(page);
  assert.ok(distance(joints.bob_rod.a, [1.5, 2, 2.5]) < 1e-6);
  assert.ok(distance(joints.bob_rod.b, bodies.bob) < CLOSE, `rod end drawn at ${joints.bob_rod.b}, the bob at ${bodies.bob}`);
  assert.ok(Math.abs(distance(joints.bob_rod.a, bodies.bob) - 1) < CLOSE, "the rod's length");
  assert.ok(distance(joints.bob_spring.a, bodies.bob) < CLOSE);
  await lookAtEverything(page);
  await sleep(300);
  await screenshot(page, "joints-spawned");
  noConsoleErrors();
});

test("a replayed record draws the joints and their states", async () => {
  const replay = await openPage(browser, await rbview("--log", record));
  await replay.waitForFunction((n) => rbview.state.replay && rbview.jointsDrawn() === n && rbview.state.joints,
    JOINTS, { timeout: 20000 });
  // Seek to the end: each row's joints come with it.
  await replay.evaluate(() => {
    const timeline = document.getElementById("timeline");
    timeline.value = rbview.state.replay.last;
    timeline.dispatchEvent(new Event("input"));
  });
  await replay.waitForFunction(() => rbview.viewer.frameDrawn && rbview.viewer.frameDrawn.step === rbview.state.replay.last_step
    && rbview.state.joints.step === rbview.viewer.frameDrawn.step, null, { timeout: 10000 });
  const { joints, bodies } = await drawn(replay);
  assert.ok(distance(joints.lamp_rope.b, bodies.lamp) < CLOSE, `rope end drawn at ${joints.lamp_rope.b}, the lamp at ${bodies.lamp}`);
  assert.ok(distance(joints.elbow.b, bodies.upper_arm) < CLOSE);
  await lookAtEverything(replay);
  await sleep(500);
  await screenshot(replay, "joints-replay");
  noConsoleErrors(replay);
  await replay.close();
});
