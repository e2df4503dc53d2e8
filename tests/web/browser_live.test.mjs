// rbview against a live rbserver, in Debian's headless chromium. The server
// starts paused on worlds/viewer.yaml (drop_box 30 m up, a pushable slider).
// Screenshots: BUILD/tests/web/artifacts/live-*.png.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import {
  rbserver, rbview, launchBrowser, openPage, screenshot, foreground, act, waitForAck, hudStep, hudStepOnceShown, sleep,
  stopAll, logs, runPython,
} from "./browser_support.mjs";

let browser, page, url;

before(async () => {
  rbserver("--paused");
  url = await rbview();
  browser = await launchBrowser();
  page = await openPage(browser, url);
});

after(async () => {
  if (browser) await browser.close();
  stopAll();
});

function noConsoleErrors() {
  assert.deepEqual(page.errors, [], `console errors:\n${page.errors.join("\n")}\n${logs()}`);
}

test("the page loads with no console error and shows every body of the world", async () => {
  await page.waitForFunction(() => rbview.state.status, null, { timeout: 10000 });
  assert.equal(await page.locator("#hud-bodies").textContent(), "8");
  const counts = await page.evaluate(() => ({
    world: rbview.state.world.bodies.length,
    status: rbview.state.status.num_bodies,
    drawn: rbview.state.frame.numBodies,
    instances: rbview.viewer.groups.reduce((n, g) => n + g.mesh.count, 0),
    planes: rbview.viewer.planes.length,
  }));
  assert.equal(counts.status, 8, "the server's own body count");
  assert.equal(counts.world, 8);
  assert.equal(counts.drawn, 8);
  // 7 bodies of one piece each, the dumbbell of three, and the ground plane.
  assert.equal(counts.instances, 6 + 3);
  assert.equal(counts.planes, 1);
  assert.equal(await page.locator("#hud-connection").textContent(), "live");
  await screenshot(page, "live-loaded");
  noConsoleErrors();
});

test("a falling box is drawn lower a second later", async () => {
  // Look up at drop_box from below its path: only the sky behind it (the ground
  // plane's far edge stays under the bottom of the view).
  assert.equal(await hudStep(page), 0, "the server should be paused at step 0");
  await page.evaluate(() => rbview.lookAt([0, 0, 27], [0, -16, 20]));
  await sleep(300);
  const region = { x: 400, y: 0, width: 200, height: 700 };
  const z0 = (await page.evaluate(() => rbview.drawnPosition("drop_box")))[2];
  const a = await screenshot(page, "live-fall-before");
  // One simulated second, exactly: STEP 1000 (dt 1 ms) from the paused start,
  // whatever the load on the machine.
  await page.fill("#step-count", "1000");
  assert.match(await act(page, "btn-step"), /step 1000: accepted/);
  await page.waitForFunction(() => rbview.viewer.frameDrawn && rbview.viewer.frameDrawn.step === 1000,
    null, { timeout: 30000 });
  await page.fill("#step-count", "10");
  await sleep(300);
  const z1 = (await page.evaluate(() => rbview.drawnPosition("drop_box")))[2];
  const b = await screenshot(page, "live-fall-after");
  const before = await foreground(page, a.png, region);
  const later = await foreground(page, b.png, region);
  assert.ok(before.count > 100 && later.count > 100, `box not seen: ${before.count} then ${later.count} pixels`);
  assert.ok(later.cy - before.cy > 60, `box centroid went from y=${before.cy} to ${later.cy} px only (z ${z0} -> ${z1} m)`);
  // Free fall for 1 s from rest (semi-implicit Euler, 1000 steps: g dt^2 n (n + 1) / 2).
  assert.ok(Math.abs(z0 - z1 - 9.81e-6 * 1000 * 1001 / 2) < 1e-3, `drawn z went from ${z0} to ${z1} m`);
  noConsoleErrors();
});

test("pause stops the step counter and resume starts it", async () => {
  assert.equal(await page.locator("#hud-paused").textContent(), "paused");
  const s1 = await hudStep(page);
  await sleep(1000);
  assert.equal(await hudStep(page), s1, "the step counter moved while paused");
  assert.match(await act(page, "btn-resume"), /resume: accepted/);
  // While states arrive at 60 Hz the HUD's step text changes at most ~10 times a second.
  await page.evaluate(() => {
    window.hudStepWrites = 0;
    new MutationObserver((records) => { window.hudStepWrites += records.length; })
      .observe(document.getElementById("hud-step"), { childList: true, characterData: true, subtree: true });
  });
  await sleep(1000);
  const writes = await page.evaluate(() => window.hudStepWrites);
  assert.ok(writes >= 3 && writes <= 12, `the HUD's step was written ${writes} times in 1 s (10 Hz expected)`);
  const s2 = await hudStep(page);
  assert.ok(s2 > s1 + 300, `after 1 s running the step went from ${s1} to ${s2} only`);
  assert.match(await act(page, "btn-pause"), /pause: accepted/);
  await sleep(300);
  const s3 = await hudStep(page);
  await sleep(1000);
  assert.equal(await hudStep(page), s3, "the step counter moved after PAUSE");
  noConsoleErrors();
});

test("a rejected command shows the server's reason", async () => {
  await page.evaluate(() => rbview.lookAt([0, 0, 0.5], [6, -9, 5]));
  assert.match(await act(page, "btn-resume"), /resume: accepted/);
  // STEP is only taken while paused.
  assert.match(await act(page, "btn-step"), /step 10: rejected: STEP needs the server to be paused/);
  assert.match(await act(page, "btn-pause"), /pause: accepted/);
  await page.fill("#step-count", "0");
  assert.match(await act(page, "btn-step"), /step 0: rejected: .*num_steps/);
  await page.fill("#step-count", "10");
  const s1 = await hudStep(page);
  assert.match(await act(page, "btn-step"), /step 10: accepted/);
  await page.waitForFunction((s) => Number(document.getElementById("hud-step").textContent) >= s + 10, s1);
  await screenshot(page, "live-rejected");
  noConsoleErrors();
});

async function drag(name, dx, dy) {
  // Look down at the body from its side, so that nothing stands in front of it.
  await page.evaluate((n) => {
    const p = rbview.drawnPosition(n);
    rbview.lookAt(p, [p[0], p[1] - 3, p[2] + 2.5]);
  }, name);
  await sleep(300);
  const at = await page.evaluate((n) => rbview.screenOf(n), name);
  const picked = await page.evaluate(({ x, y }) => {
    const hit = rbview.viewer.pick(x, y, false);
    return hit ? rbview.state.world.bodies[hit.body].name : null;
  }, at);
  assert.equal(picked, name, `the body under ${name}'s centre on screen is ${picked}`);
  await page.evaluate(() => { document.getElementById("message").textContent = ""; });
  await page.mouse.move(at.x, at.y);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) await page.mouse.move(at.x + (dx * i) / 10, at.y + (dy * i) / 10);
  await page.mouse.up();
  return waitForAck(page);
}

test("dragging a body pushes it: the ack arrives and its velocity changes in RBSIM_STATE", async () => {
  assert.match(await act(page, "btn-resume"), /resume: accepted/);
  const watcher = await runPython("watch_body.py", ["slider", "0.2", "10"]);
  await watcher.printed("watching");
  const text = await drag("slider", 150, 0);
  assert.match(text, /push slider with [0-9.]+ N for 0.25 s: accepted \(from step \d+\)/);
  await screenshot(page, "live-push-arrow");
  const { code, stdout } = await watcher.done;
  assert.equal(code, 0, `slider never moved faster than 0.2 m/s: ${stdout}`);
  const moved = await page.evaluate(() => rbview.drawnPosition("slider"));
  assert.ok(Math.abs(moved[0] + 1.5) > 0.01 || Math.abs(moved[1] - 1.0) > 0.01, `slider drawn at ${moved}`);
  // The ball is not in limits.wrench_bodies: the push is refused and the reason shown.
  const refused = await drag("ball", 100, 0);
  assert.match(refused, /push ball .*: rejected: body 'ball' does not accept external wrenches/);
  noConsoleErrors();
});

test("contacts, names on hover, selection, follow and plots", async () => {
  await page.evaluate(() => rbview.lookAt([0, 0, 0.5], [6, -9, 5]));
  await page.check("#toggle-contacts");
  await page.waitForFunction(() => rbview.viewer.contactPoints.visible && rbview.state.frame.numContacts > 0);
  const at = await page.evaluate(() => rbview.screenOf("can"));
  await page.mouse.move(at.x, at.y);
  await page.waitForFunction(() => document.getElementById("tooltip").textContent === "can"
    && !document.getElementById("tooltip").classList.contains("hidden"), null, { timeout: 30000 });
  await page.mouse.click(at.x, at.y);
  assert.match(await page.locator("#hud-selected").textContent(), /^can \(cylinder/);
  await page.check("#toggle-follow");
  await page.check("#toggle-plots");
  await sleep(1500);
  const view = await page.evaluate(() => ({
    target: rbview.viewer.controls.target.toArray(),
    can: rbview.drawnPosition("can"),
    plotted: rbview.viewer && document.querySelectorAll("#plots .uplot").length,
  }));
  for (let k = 0; k < 3; k++) assert.ok(Math.abs(view.target[k] - view.can[k]) < 1e-3, `camera target ${view.target} is not the can ${view.can}`);
  assert.equal(view.plotted, 3);
  await screenshot(page, "live-contacts-follow-plots");
  noConsoleErrors();
});

test("the real-time factor is set and reset returns to the initial world", async () => {
  await page.fill("#rtf-value", "0.5");
  assert.match(await act(page, "btn-rtf"), /real-time factor 0.5: accepted/);
  await page.waitForFunction(() => rbview.state.status.target_rtf === 0.5, null, { timeout: 30000 });
  await page.waitForFunction(() => document.getElementById("hud-rtf").textContent.includes("target 0.50"));
  await page.fill("#rtf-value", "-1");
  assert.match(await act(page, "btn-rtf"), /real-time factor -1: rejected: .+/);
  const revision = await page.evaluate(() => rbview.state.world.revision);
  assert.match(await act(page, "btn-pause"), /pause: accepted/);
  assert.match(await act(page, "btn-reset"), /reset: accepted/);
  await page.waitForFunction((r) => rbview.state.world.revision > r && rbview.viewer.frameDrawn
    && rbview.viewer.frameDrawn.revision === rbview.state.world.revision, revision, { timeout: 30000 });
  const z = (await page.evaluate(() => rbview.drawnPosition("drop_box")))[2];
  assert.ok(Math.abs(z - 30) < 1e-3, `after reset drop_box is drawn at z=${z}, not 30`);
  assert.equal(await hudStepOnceShown(page, 0), 0);
  assert.equal(await page.locator("#hud-bodies").textContent(), "8");
  noConsoleErrors();
});

test("with --read-only the controls are off", async () => {
  const readOnlyUrl = await rbview("--read-only");
  const other = await openPage(browser, readOnlyUrl);
  assert.equal(await other.locator("#hud-connection").textContent(), "live (read-only)");
  assert.ok(await other.locator("#btn-pause").isDisabled());
  assert.match(await other.locator("#message").textContent(), /read-only/);
  await other.screenshot({ path: `${process.env.RBVIEW_ARTIFACTS || "."}/live-read-only.png` });
  assert.deepEqual(other.errors, []);
  await other.close();
});
