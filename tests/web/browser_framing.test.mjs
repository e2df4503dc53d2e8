// rbview's first view and its framing controls, in Debian's headless chromium:
// rbserver paused on config/worlds/robot_arm.yaml (a seven-joint arm about
// 1 m tall and two 10 cm boxes). The page opens framed on the bodies (before,
// the arm was some 60 px tall in a 700 px view), but for a stray 40 m above
// them; "Frame all" (key A) and "Frame selected" (key F) bring them back after
// the view has wandered off.
// Screenshots: BUILD/tests/web/artifacts/framing-*.png.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import path from "node:path";
import {
  repo, build, artifacts, startProcess, rbview, launchBrowser, openPage, screenshot, colouredBounds, countColours, hidePanels,
  sleep, stopAll, logs, runPython,
} from "./browser_support.mjs";

const world = path.join(repo, "config", "worlds", "robot_arm.yaml");
const VIEW = { width: 1000, height: 700 };

let browser, page, url;

before(async () => {
  startProcess("rbserver", path.join(build, "server", "daemon", "rbserver"),
    ["--config", world, "--paused", "--log-level", "info"]);
  browser = await launchBrowser();
  url = await rbview();
  page = await openPage(browser, url, VIEW);
});

after(async () => {
  if (browser) await browser.close();
  stopAll();
});

function noConsoleErrors() {
  assert.deepEqual(page.errors, [], `console errors:\n${page.errors.join("\n")}\n${logs()}`);
}

// A screenshot without the panels and the joints' axes (drawn in colour, and
// longer than the links).
async function bodiesOnly(name) {
  await page.uncheck("#toggle-joints");
  await hidePanels(page);
  await sleep(200);
  const { png } = await screenshot(page, name);
  await hidePanels(page, false);
  await page.check("#toggle-joints");
  return png;
}

// The bodies' pixels: {count, left, top, right, bottom}.
async function bodiesOnScreen(name) {
  return colouredBounds(page, await bodiesOnly(name));
}

// Which share of the view's width or height (the larger) a rectangle spans.
const share = (r) => Math.max((r.right - r.left) / VIEW.width, (r.bottom - r.top) / VIEW.height);
const inside = (r, margin = 0) => r.left >= margin && r.top >= margin
  && r.right <= VIEW.width - margin && r.bottom <= VIEW.height - margin;

// Looks at empty ground 30 m away from the bodies, which then are a speck or off screen.
async function lookAway() {
  await page.evaluate(() => rbview.lookAt([30, 30, 0], [40, 20, 8]));
  await sleep(100);
  const away = await page.evaluate(() => rbview.screenRect());
  assert.ok(!inside(away) || share(away) < 0.05, `still framed after looking away: ${JSON.stringify(away)}`);
}

test("the first view frames the arm and its boxes", async () => {
  // What is drawn, measured on the screenshot: the coloured (dynamic) bodies
  // are large and in view, clear of its edges.
  await screenshot(page, "framing-start-page");
  const pixels = await bodiesOnScreen("framing-start");
  assert.ok(pixels.count > 5000, `only ${pixels.count} pixels of bodies: ${JSON.stringify(pixels)}`);
  assert.ok(pixels.bottom - pixels.top > 0.4 * VIEW.height,
    `the bodies are drawn ${pixels.bottom - pixels.top} px tall of ${VIEW.height}: ${JSON.stringify(pixels)}`);
  assert.ok(inside(pixels, 5), `bodies cut by the view's edge: ${JSON.stringify(pixels)}`);
  // The box around them, projected: all in view, and filling most of it.
  const rect = await page.evaluate(() => rbview.screenRect());
  assert.ok(inside(rect), `the bodies' box is not all in view: ${JSON.stringify(rect)}`);
  assert.ok(share(rect) > 0.5, `the bodies' box spans ${share(rect)} of the view only: ${JSON.stringify(rect)}`);
  noConsoleErrors();
});

test("the ground's grid is drawn under the bodies, up to the camera", async () => {
  // The grid's lines are unlit, in their own colours (clients/web/src/scene.js):
  // the near third of the view, in front of the bodies, must cross some.
  const png = await bodiesOnly("framing-grid");
  const near = { x: 0, y: Math.round((2 * VIEW.height) / 3), width: VIEW.width, height: Math.round(VIEW.height / 3) };
  const lines = await countColours(page, png, near, [0x6b7385, 0x4c566a]);
  assert.ok(lines > 300, `only ${lines} pixels of grid lines in the near third of the view`);
});

test("Frame all (button and key A) frames every body again", async () => {
  await lookAway();
  await page.click("#btn-frame-all");
  let rect = await page.evaluate(() => rbview.screenRect());
  assert.ok(inside(rect) && share(rect) > 0.5, `after Frame all: ${JSON.stringify(rect)}`);
  const pixels = await bodiesOnScreen("framing-frame-all");
  assert.ok(pixels.count > 5000 && pixels.bottom - pixels.top > 0.3 * VIEW.height && inside(pixels, 5),
    `after Frame all: ${JSON.stringify(pixels)}`);

  // A clicked checkbox keeps the focus: the keys work there too.
  await lookAway();
  await page.focus("#toggle-contacts");
  await page.keyboard.press("a");
  rect = await page.evaluate(() => rbview.screenRect());
  assert.ok(inside(rect) && share(rect) > 0.5, `after key A: ${JSON.stringify(rect)}`);

  // Not while typing in a field of the controls.
  await lookAway();
  const camera = await page.evaluate(() => rbview.camera());
  await page.focus("#step-count");
  await page.keyboard.press("a");
  assert.deepEqual(await page.evaluate(() => rbview.camera()), camera, "key A in the step field moved the camera");
  await page.evaluate(() => document.activeElement.blur());
  noConsoleErrors();
});

test("Frame selected (button and key F) frames the selected body", async () => {
  await page.click("#btn-frame-selected");
  assert.equal(await page.locator("#message").textContent(), "frame selected: no body selected (click one)");

  await page.keyboard.press("a");
  // The box's place on screen once the view is still: the same camera over
  // two drawn frames (the frame all and the bodies' last state drawn), so
  // that the click lands where the box is drawn.
  await page.waitForFunction(() => new Promise((resolve) => {
    const before = JSON.stringify([rbview.camera(), rbview.screenOf("right_box")]);
    requestAnimationFrame(() => requestAnimationFrame(() =>
      resolve(before === JSON.stringify([rbview.camera(), rbview.screenOf("right_box")]))));
  }));
  const at = await page.evaluate(() => rbview.screenOf("right_box"));
  await page.mouse.click(at.x, at.y);
  // Once (at load 7 on two cores, 6 frames/s) the click selected nothing:
  // should it again, the message says what was under the pointer.
  const selected = await page.locator("#hud-selected").textContent();
  const under = selected.startsWith("right_box") ? null : await page.evaluate(({ x, y }) => {
    const element = document.elementFromPoint(x, y);
    const hit = rbview.viewer.pick(x, y, false);
    return { element: element && (element.id || element.tagName), matches: rbview.viewer.frameMatchesWorld(),
      hit: hit && rbview.state.world.bodies[hit.body].name, fps: rbview.state.fps };
  }, at);
  assert.match(selected, /^right_box \(box/, `clicked at ${JSON.stringify(at)}: ${JSON.stringify(under)}`);

  for (const how of ["button", "key F"]) {
    await lookAway();
    if (how === "button") await page.click("#btn-frame-selected");
    else await page.keyboard.press("f");
    const view = await page.evaluate(() => ({
      rect: rbview.screenRect("right_box"), camera: rbview.camera(), box: rbview.drawnPosition("right_box"),
    }));
    // The camera looks at the 10 cm box from close by, and the box fills the view.
    const offset = Math.hypot(...view.camera.target.map((v, k) => v - view.box[k]));
    const distance = Math.hypot(...view.camera.position.map((v, k) => v - view.camera.target[k]));
    assert.ok(offset < 1e-3, `${how}: the camera looks at ${view.camera.target}, the box is at ${view.box}`);
    assert.ok(distance < 0.5, `${how}: the camera is ${distance} m from the 10 cm box`);
    assert.ok(inside(view.rect) && share(view.rect) > 0.5, `${how}: the box spans ${JSON.stringify(view.rect)}`);
  }
  assert.equal(await page.locator("#message").textContent(), "", "the note stays once framing worked");
  const pixels = await bodiesOnScreen("framing-frame-selected");
  assert.ok(pixels.bottom - pixels.top > 0.3 * VIEW.height, `the selected box: ${JSON.stringify(pixels)}`);
  noConsoleErrors();
});

test("the first view leaves out a body far from the others; Frame all takes it too", async () => {
  // Last: it changes the world. A box 40 m above the arm (SPAWN, paused).
  const revision = await page.evaluate(() => rbview.state.world.revision);
  const spawn = await runPython("spawn_world_part.py", [path.join(repo, "tests", "web", "worlds", "far_box.yaml")]);
  const { code, stdout } = await spawn.done;
  assert.equal(code, 0, `SPAWN refused: ${stdout}`);
  await page.waitForFunction((r) => rbview.state.world.revision > r, revision, { timeout: 10000 });

  const fresh = await openPage(browser, url, VIEW);
  const names = await fresh.evaluate(() => rbview.state.world.bodies.map((b) => b.name));
  assert.ok(names.includes("far_box"), names.join(", "));
  const gathered = names.filter((n) => n !== "far_box" && n !== "ground");
  let view = await fresh.evaluate((g) => ({ arm: rbview.screenRect(...g), far: rbview.screenRect("far_box") }), gathered);
  assert.ok(inside(view.arm) && share(view.arm) > 0.5, `first view, the arm world: ${JSON.stringify(view.arm)}`);
  assert.ok(!inside(view.far), `first view, far_box: ${JSON.stringify(view.far)}`);
  await fresh.screenshot({ path: path.join(artifacts, "framing-stray-start.png") });

  await fresh.click("#btn-frame-all");
  view = await fresh.evaluate((g) => ({ arm: rbview.screenRect(...g), all: rbview.screenRect() }), gathered);
  assert.ok(inside(view.all) && share(view.all) > 0.5, `Frame all: every body ${JSON.stringify(view.all)}`);
  assert.ok(share(view.arm) < 0.1, `Frame all: the arm world ${JSON.stringify(view.arm)}, 40 m below far_box`);
  await fresh.screenshot({ path: path.join(artifacts, "framing-stray-frame-all.png") });
  assert.deepEqual(fresh.errors, []);
  await fresh.close();
});
