// rbview draws a static trimesh body (worlds/trimesh.yaml: an open ramp and a
// ball) from the vertices and triangles the server sends, as it draws a mesh.
// Screenshots: BUILD/tests/web/artifacts/trimesh-*.png.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import path from "node:path";
import { fileURLToPath } from "node:url";
import {
  build, startProcess, rbview, launchBrowser, openPage, screenshot, stopAll,
} from "./browser_support.mjs";

const here = path.dirname(fileURLToPath(import.meta.url));
let browser, page;

before(async () => {
  startProcess("rbserver", path.join(build, "server", "daemon", "rbserver"),
    ["--config", path.join(here, "worlds", "trimesh.yaml"), "--log-level", "info", "--paused"]);
  browser = await launchBrowser();
  page = await openPage(browser, await rbview());
});

after(async () => {
  if (browser) await browser.close();
  stopAll();
});

test("a trimesh body is drawn from its triangles", async () => {
  const seen = await page.evaluate(() => {
    const ramp = rbview.state.world.bodies.find((b) => b.name === "ramp");
    return {
      type: ramp.shape_type,
      vertices: ramp.vertices.length / 3, // flat arrays, as the page keeps them
      triangles: ramp.triangles.length / 3,
      bodies: rbview.state.frame.numBodies,
      instances: rbview.viewer.groups.reduce((n, g) => n + g.mesh.count, 0),
    };
  });
  assert.deepEqual(seen, { type: "trimesh", vertices: 4, triangles: 2, bodies: 2, instances: 2 });
  await screenshot(page, "trimesh-loaded");
  assert.deepEqual(page.errors, []);
});
