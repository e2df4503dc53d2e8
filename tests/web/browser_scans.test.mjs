// rbview's rays, in Debian's headless chromium: rbserver live on
// config/worlds/sensors.yaml (a lidar on a cart in a 6 m x 4 m room, a range
// finder looking down from the ceiling). The "rays" menu lists the range
// sensors heard; choosing one draws a line from its origin to each hit and a
// dot at the hit, where the scan's ranges put them. Screenshot:
// BUILD/tests/web/artifacts/scans-lidar.png.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import path from "node:path";
import {
  repo, build, startProcess, rbview, launchBrowser, openPage, screenshot, sleep, stopAll, logs,
} from "./browser_support.mjs";

const world = path.join(repo, "config", "worlds", "sensors.yaml");
const rbserverPath = path.join(build, "server", "daemon", "rbserver");

let browser, page;

before(async () => {
  startProcess("rbserver", rbserverPath, ["--config", world, "--log-level", "info"]);
  browser = await launchBrowser();
  page = await openPage(browser, await rbview());
});

after(async () => {
  if (browser) await browser.close();
  stopAll();
});

test("the rays menu lists the range sensors and draws nothing until one is chosen", async () => {
  await page.waitForFunction(() => rbview.scans.names().length === 2, null, { timeout: 20000 });
  const options = await page.evaluate(() => [...document.getElementById("scan-sensor").options].map((o) => o.value));
  assert.deepEqual(options, ["", "cart_lidar", "floor_range"], logs());
  const visible = await page.evaluate(() => rbview.scans.rays.visible || rbview.scans.hits.visible);
  assert.equal(visible, false);
  assert.deepEqual(page.errors, []);
});

test("choosing the lidar draws its beams from its origin to the room's walls and floor", async () => {
  await page.selectOption("#scan-sensor", "cart_lidar");
  await page.waitForFunction(() => rbview.scans.hits.visible && rbview.scans.hits.geometry.drawRange.count > 100,
    null, { timeout: 10000 });
  const drawn = await page.evaluate(() => {
    const n = rbview.scans.hits.geometry.drawRange.count;
    const points = Array.from(rbview.scans.hits.geometry.attributes.position.array.subarray(0, 3 * n));
    const lines = Array.from(rbview.scans.rays.geometry.attributes.position.array.subarray(0, 6));
    return { n, points, firstLine: lines, origin: rbview.scans.drawnScan.origin, info: document.getElementById("scan-info").textContent };
  });
  assert.ok(drawn.n <= 2048, `${drawn.n} beams drawn`);
  for (let i = 0; i < drawn.n; i++) {
    const [x, y, z] = drawn.points.slice(3 * i, 3 * i + 3);
    assert.ok(Math.abs(x) <= 3.05 && Math.abs(y) <= 2.05 && z >= -0.05 && z <= 1.05, `hit ${i} at ${x} ${y} ${z}`);
  }
  assert.deepEqual(drawn.firstLine.slice(0, 3).map((v) => Math.round(v * 1e4) / 1e4),
    drawn.origin.map((v) => Math.round(v * 1e4) / 1e4), "each ray starts at the sensor's origin");
  assert.match(drawn.info, /of 28800 beams returned/);
  await page.evaluate(() => rbview.lookAt([0, 0, 0.3], [4, -6, 5]));
  await sleep(500);
  await screenshot(page, "scans-lidar");
  assert.deepEqual(page.errors, []);
});

test("the range finder draws its one beam down to the floor; none hides the rays", async () => {
  await page.selectOption("#scan-sensor", "floor_range");
  await page.waitForFunction(() => rbview.scans.drawnScan && rbview.scans.drawnScan.name === "floor_range",
    null, { timeout: 10000 });
  const hit = await page.evaluate(() => Array.from(rbview.scans.hits.geometry.attributes.position.array.subarray(0, 3)));
  assert.ok(Math.hypot(hit[0] + 1.5, hit[1] + 1, hit[2]) < 1e-3, `floor hit drawn at ${hit}`);
  await page.selectOption("#scan-sensor", "");
  const visible = await page.evaluate(() => rbview.scans.rays.visible || rbview.scans.hits.visible);
  assert.equal(visible, false);
  assert.deepEqual(page.errors, []);
});
