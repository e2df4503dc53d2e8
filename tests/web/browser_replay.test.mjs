// rbview --log: an rbserver --record file of worlds/viewer.yaml (2 s, as fast as
// possible) replayed in headless chromium: play, pause, scrub, speed; seeking
// keeps the pause state; the poses shown at a step are that step's.
// Screenshots: BUILD/tests/web/artifacts/replay-*.png.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import path from "node:path";
import {
  rbserver, rbview, launchBrowser, openPage, screenshot, sleep, stopAll, logs, artifacts, hudStepOnceShown,
} from "./browser_support.mjs";

let browser, page;
const record = path.join(artifacts, "..", "replay-session.lcmlog");
const G = 9.81, DT = 0.001, Z0 = 30;

before(async () => {
  const server = rbserver("--real-time-factor", "0", "--duration", "2", "--record", record);
  const code = await new Promise((resolve) => server.on("exit", resolve));
  assert.equal(code, 0, `rbserver --record exited with ${code}\n${logs()}`);
  browser = await launchBrowser();
  page = await openPage(browser, await rbview("--log", record));
  await page.waitForFunction(() => rbview.state.replay);
});

after(async () => {
  if (browser) await browser.close();
  stopAll();
});

const replay = () => page.evaluate(() => rbview.state.replay);

// drop_box falls freely (semi-implicit Euler: z_n = z0 - g dt^2 n (n + 1) / 2) until it lands at ~2.47 s.
function dropZ(step) {
  return Z0 - G * DT * DT * step * (step + 1) / 2;
}

async function seek(index) {
  await page.evaluate((i) => {
    const timeline = document.getElementById("timeline");
    timeline.value = i;
    timeline.dispatchEvent(new Event("input"));
  }, index);
  await page.waitForFunction((i) => rbview.state.replay.index === i && rbview.viewer.frameDrawn
    && rbview.viewer.frameDrawn.step === rbview.state.replay.step, index, { timeout: 5000 });
}

test("a log loads paused at its first state, with the controls off", async () => {
  const r = await replay();
  assert.equal(r.playing, false);
  assert.equal(r.index, 0);
  assert.ok(r.last > 60, `only ${r.last + 1} states in the log`);
  assert.equal(await page.locator("#hud-connection").textContent(), "replaying a log");
  assert.ok(!(await page.locator("#replay").isHidden()));
  assert.ok(await page.locator("#btn-pause").isDisabled());
  assert.equal(await page.locator("#hud-bodies").textContent(), "8");
  assert.deepEqual(page.errors, []);
});

test("scrubbing to a step shows that step's poses, and seeking keeps the pause state", async () => {
  const r = await replay();
  const index = Math.floor(r.last * 0.6);
  await seek(index);
  const after = await replay();
  assert.equal(after.playing, false, "seeking started playback");
  const step = after.step;
  const drawn = await page.evaluate(() => rbview.drawnPosition("drop_box"));
  assert.ok(Math.abs(drawn[2] - dropZ(step)) < 1e-3, `drop_box drawn at z=${drawn[2]}, at step ${step} it was at ${dropZ(step)}`);
  assert.equal(await hudStepOnceShown(page, step), step);
  await page.evaluate(() => rbview.lookAt([0, 0, 20], [0, -25, 15]));
  await sleep(500);
  assert.equal((await replay()).index, index, "a paused replay moved on");
  await screenshot(page, "replay-scrubbed");
  assert.deepEqual(page.errors, []);
});

test("play advances, pause stops, and a seek while playing plays on", async () => {
  await seek(0);
  await page.selectOption("#replay-speed", "0.5");
  await page.waitForFunction(() => rbview.state.replay.speed === 0.5);
  await page.click("#btn-play");
  await page.waitForFunction(() => rbview.state.replay.playing);
  await sleep(1000);
  const playing = await replay();
  // 1 s of wall clock at 0.5x is about 0.5 s of the log (at most: the page may be slow).
  assert.ok(playing.sim_time > 0.05 && playing.sim_time < 0.8, `after 1 s at 0.5x the replay is at ${playing.sim_time} s`);
  await seek(10);
  await sleep(500);
  const still = await replay();
  assert.equal(still.playing, true, "seeking paused playback");
  assert.ok(still.index > 10, "playback did not go on after the seek");
  await page.click("#btn-play"); // now "Pause"
  await page.waitForFunction(() => !rbview.state.replay.playing);
  const stopped = (await replay()).index;
  await sleep(500);
  assert.equal((await replay()).index, stopped, "the replay moved while paused");
  assert.deepEqual(page.errors, []);
});
