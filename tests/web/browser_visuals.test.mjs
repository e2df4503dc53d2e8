// Robots drawn as themselves, in Debian's headless chromium: rbserver on
// tests/web/worlds/robot_visuals/visual_robot.yaml (a pillar holding a block
// whose <visual> is an STL mesh in magenta), rbview serving that directory's
// meshes (--meshes). The block is drawn from its mesh, in its colour, where
// its link is; with the collision toggle on, from its collision box instead
// (no magenta); the page draws a ground under it. Then the KUKA iiwa of
// bench/robots/data with <visual> elements put back (its STL meshes, the
// original's Grey and Orange materials), for a look. Then two example worlds
// of public robots, served as `rbview --meshes config` serves them: the UR5e
// (config/worlds/ur5e.yaml), drawn from its COLLADA files in their own
// colours, and the Franka Panda (config/worlds/panda.yaml), drawn from its
// OBJ files in its URDF's white, fingers and all.
// Screenshots: BUILD/tests/web/artifacts/visuals-*.png.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { copyFileSync, mkdirSync, readFileSync, readdirSync, writeFileSync } from "node:fs";
import path from "node:path";
import {
  repo, build, startProcess, rbview, launchBrowser, openPage, screenshot, hidePanels, sleep, stopAll, logs,
} from "./browser_support.mjs";

const worldDir = path.join(repo, "tests", "web", "worlds", "robot_visuals");
const configDir = path.join(repo, "config");
const VIEW = { width: 1000, height: 700 };
const work = process.env.RBVIEW_WORK || path.join(build, "tests", "web", "work", "browser_visuals");

let browser;

before(async () => {
  browser = await launchBrowser();
});

after(async () => {
  if (browser) await browser.close();
  stopAll();
});

// Pixels of a screenshot in `region` whose colour is magenta-like however lit
// (red and blue well above green, and close to each other): {count, cx, cy}.
async function magenta(page, png, region) {
  return page.evaluate(async ({ data, region: r }) => {
    const image = new Image();
    image.src = `data:image/png;base64,${data}`;
    await image.decode();
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext("2d");
    context.drawImage(image, 0, 0);
    const x0 = Math.max(0, Math.round(r.x)), y0 = Math.max(0, Math.round(r.y));
    const w = Math.min(image.width - x0, Math.round(r.width)), h = Math.min(image.height - y0, Math.round(r.height));
    const pixels = context.getImageData(x0, y0, w, h).data;
    let count = 0, sx = 0, sy = 0;
    for (let y = 0; y < h; y++) {
      for (let x = 0; x < w; x++) {
        const o = 4 * (y * w + x);
        const red = pixels[o], green = pixels[o + 1], blue = pixels[o + 2];
        if (red > green + 70 && blue > green + 70 && Math.abs(red - blue) < 50) {
          count++; sx += x0 + x; sy += y0 + y;
        }
      }
    }
    return { count, cx: count ? sx / count : NaN, cy: count ? sy / count : NaN };
  }, { data: png.toString("base64"), region });
}

async function waitForVisuals(page) {
  await page.waitForFunction(() => rbview.visualsDrawn() > 0 && rbview.visualsPending() === 0, null,
    { timeout: 20000 });
  await sleep(300); // a few frames with the meshes in
}

test("a link's visual mesh is drawn in its colour where the link is", async () => {
  startProcess("rbserver", path.join(build, "server", "daemon", "rbserver"),
    ["--config", path.join(worldDir, "visual_robot.yaml"), "--log-level", "info"]);
  const url = await rbview("--meshes", worldDir);
  const page = await openPage(browser, url, VIEW);
  try {
    await waitForVisuals(page);
    assert.deepEqual(await page.evaluate(() => rbview.visualsFailed()), []);
    const world = await page.evaluate(() => rbview.state.world.bodies.map((b) => ({ name: b.name, visuals: b.visuals })));
    const block = world.find((b) => b.name === "arm/block");
    assert.equal(block.visuals.length, 1, JSON.stringify(world));
    assert.equal(block.visuals[0].mesh_url, "world/meshes/block.stl");
    assert.deepEqual(block.visuals[0].rgba, [1, 0, 1, 1]);

    await hidePanels(page);
    await screenshot(page, "visuals-robot-page");
    const { png } = await screenshot(page, "visuals-robot");
    // Where the block's link is on screen, and the size of its 0.3 m cube there.
    const where = await page.evaluate(() => {
      const centre = rbview.screenOf("arm/block");
      const i = rbview.bodyIndex("arm/block");
      const p = rbview.viewer.bodyPosition(i);
      const edge = rbview.viewer.screenPoint(p.clone().setZ(p.z + 0.15));
      return { centre, half: Math.hypot(edge.x - centre.x, edge.y - centre.y) };
    });
    const r = Math.max(20, 2 * where.half);
    const near = await magenta(page, png, { x: where.centre.x - r, y: where.centre.y - r, width: 2 * r, height: 2 * r });
    const all = await magenta(page, png, { x: 0, y: 0, width: VIEW.width, height: VIEW.height });
    assert.ok(near.count > 0.3 * where.half * where.half,
      `only ${near.count} magenta pixels around the block at ${JSON.stringify(where)}`);
    assert.ok(near.count >= 0.95 * all.count, `magenta away from the block: ${near.count} near it of ${all.count}`);
    assert.ok(Math.hypot(near.cx - where.centre.x, near.cy - where.centre.y) < where.half,
      `the magenta is centred at (${near.cx}, ${near.cy}), the block at ${JSON.stringify(where.centre)}`);

    // Collision shapes instead (key C): the block is drawn as its box in the
    // viewer's own colours, not magenta.
    await page.keyboard.press("c");
    await sleep(300);
    const { png: collision } = await screenshot(page, "visuals-robot-collision");
    const none = await magenta(page, collision, { x: 0, y: 0, width: VIEW.width, height: VIEW.height });
    assert.ok(none.count < 0.05 * all.count, `${none.count} magenta pixels with the collision shapes shown`);
    assert.equal(await page.evaluate(() => document.getElementById("toggle-collision").checked), true);
    await page.keyboard.press("c");
    assert.deepEqual(page.errors, [], `console errors:\n${page.errors.join("\n")}\n${logs()}`);
  } finally {
    await page.close();
    stopAll();
  }
});

// bench/robots/data/kuka_iiwa has its meshes but not its <visual> elements
// (SOURCE.md): put them back (each link drawn from its own mesh, link_0 and
// link_7 in Grey, the others in Orange, as bullet3's model.urdf has them),
// copied into the test's work directory (a link out of the served directory
// would be refused).
function iiwaWithVisuals() {
  const source = path.join(repo, "bench", "robots", "data", "kuka_iiwa");
  const dir = path.join(work, "iiwa");
  mkdirSync(path.join(dir, "meshes"), { recursive: true });
  for (const name of readdirSync(path.join(source, "meshes"))) {
    copyFileSync(path.join(source, "meshes", name), path.join(dir, "meshes", name));
  }
  const urdf = readFileSync(path.join(source, "model.urdf"), "utf8").replace(
    /<collision>\s*<origin([^>]*)\/>\s*<geometry>\s*<mesh filename="meshes\/link_(\d)\.stl"\/>\s*<\/geometry>\s*<\/collision>/g,
    (whole, origin, n) => `<visual><origin${origin}/><geometry><mesh filename="meshes/link_${n}.stl"/></geometry>`
      + `<material name="${n === "0" || n === "7" ? "Grey" : "Orange"}"/></visual>\n    ${whole}`);
  assert.equal((urdf.match(/<visual><origin/g) || []).length, 8,
    "each collision mesh of the iiwa gets its visual");
  writeFileSync(path.join(dir, "model.urdf"), urdf);
  writeFileSync(path.join(dir, "iiwa.yaml"), [
    "world: {dt: 0.001, gravity: [0, 0, -9.81]}",
    "lcm: {state_rate: 60, status_rate: 10}",
    "robots:",
    "  - name: iiwa",
    "    urdf: model.urdf",
    "    fixed_base: true",
    "    joint_positions: {lbr_iiwa_joint_2: 0.6, lbr_iiwa_joint_4: -1.2, lbr_iiwa_joint_6: 0.8}",
    "",
  ].join("\n"));
  return dir;
}

test("the KUKA iiwa is drawn from its meshes in its colours", async () => {
  const dir = iiwaWithVisuals();
  startProcess("rbserver", path.join(build, "server", "daemon", "rbserver"),
    ["--config", path.join(dir, "iiwa.yaml"), "--paused", "--log-level", "info"]);
  const url = await rbview("--meshes", dir);
  const page = await openPage(browser, url, VIEW);
  try {
    await waitForVisuals(page);
    assert.deepEqual(await page.evaluate(() => rbview.visualsFailed()), []);
    assert.ok(await page.evaluate(() => rbview.visualsDrawn()) >= 8, "the iiwa's links drawn from their visuals");
    await hidePanels(page);
    const { png } = await screenshot(page, "visuals-iiwa");
    // Orange (1, 0.42, 0.04) however lit: red well above green, green above blue.
    const orange = await page.evaluate(async (data) => {
      const image = new Image();
      image.src = `data:image/png;base64,${data}`;
      await image.decode();
      const canvas = new OffscreenCanvas(image.width, image.height);
      const context = canvas.getContext("2d");
      context.drawImage(image, 0, 0);
      const pixels = context.getImageData(0, 0, image.width, image.height).data;
      let count = 0;
      for (let o = 0; o < pixels.length; o += 4) {
        if (pixels[o] > pixels[o + 1] + 50 && pixels[o + 1] > pixels[o + 2] + 20) count++;
      }
      return count;
    }, png.toString("base64"));
    assert.ok(orange > 5000, `only ${orange} orange pixels of the iiwa`);
    // Selected: the joint markers come forward.
    await page.evaluate(() => rbview.viewer.setSelected(rbview.bodyIndex("iiwa/lbr_iiwa_link_3")));
    await sleep(200);
    await screenshot(page, "visuals-iiwa-selected");
    assert.deepEqual(page.errors, [], `console errors:\n${page.errors.join("\n")}\n${logs()}`);
  } finally {
    await page.close();
    stopAll();
  }
});

// Pixels of a screenshot in `region` of the example robots' colours, however
// lit: `urBlue` (UR's URBlue, (0.49, 0.68, 0.8) in the .dae files' effects:
// green and blue well above red, which the background, the ground and its grid,
// all slate greys, are not), `lightGrey` (UR's LinkGrey, 0.82, and the Panda's
// white: bright, channels within 24 of each other; the grid lines stay below
// 140) and `darkGrey` (UR's JointGrey, 0.28, and Black: channels within 12,
// each below 110, not the bluish slate of the ground).
async function robotColours(page, png, region) {
  return page.evaluate(async ({ data, region: r }) => {
    const image = new Image();
    image.src = `data:image/png;base64,${data}`;
    await image.decode();
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext("2d");
    context.drawImage(image, 0, 0);
    const x0 = Math.max(0, Math.round(r.x)), y0 = Math.max(0, Math.round(r.y));
    const w = Math.min(image.width - x0, Math.round(r.width)), h = Math.min(image.height - y0, Math.round(r.height));
    const pixels = context.getImageData(x0, y0, w, h).data;
    const counts = { urBlue: 0, lightGrey: 0, darkGrey: 0, all: w * h };
    for (let o = 0; o < pixels.length; o += 4) {
      const red = pixels[o], green = pixels[o + 1], blue = pixels[o + 2];
      const spread = Math.max(red, green, blue) - Math.min(red, green, blue);
      if (green > red + 25 && blue > red + 45) counts.urBlue++;
      else if (spread < 24 && Math.min(red, green, blue) > 140) counts.lightGrey++;
      else if (spread < 12 && Math.max(red, green, blue) < 110) counts.darkGrey++;
    }
    return counts;
  }, { data: png.toString("base64"), region });
}

// A screenshot with the joints' markers and axes hidden (the joints toggle):
// their blue would count as UR blue. Shown again after.
async function screenshotWithoutJoints(page, name) {
  const toggle = (on) => page.evaluate((checked) => {
    const box = document.getElementById("toggle-joints");
    box.checked = checked;
    box.dispatchEvent(new Event("change"));
  }, on);
  await toggle(false);
  await sleep(300);
  const shot = await screenshot(page, name);
  await toggle(true);
  return shot;
}

// Opens the example world `name` (config/worlds/NAME.yaml) as its comment
// says to, `rbview --meshes config`, and waits until every visual mesh of it
// has been fetched and drawn (none failed): {page, meshes}, meshes being the
// world's mesh visuals as {body, url}.
async function openExampleWorld(name) {
  startProcess("rbserver", path.join(build, "server", "daemon", "rbserver"),
    ["--config", path.join(configDir, "worlds", `${name}.yaml`), "--paused", "--log-level", "info"]);
  const url = await rbview("--meshes", configDir);
  const page = await openPage(browser, url, VIEW);
  await waitForVisuals(page);
  assert.deepEqual(await page.evaluate(() => rbview.visualsFailed()), [], logs());
  const meshes = await page.evaluate(() => rbview.state.world.bodies.flatMap((b) => (b.visuals || [])
    .filter((v) => v.kind === "mesh").map((v) => ({ body: b.name, url: v.mesh_url }))));
  return { page, meshes };
}

// Body `name`'s visual meshes lie where its collision meshes do (a URDF's
// visual and collision meshes of a link are modelled in the same frame; here
// they differ only by simplification): the world boxes around each agree
// within `tolerance` metres at every face. A mesh turned by a wrong up axis or
// scaled by a wrong unit would be metres or a quarter turn off.
async function assertVisualWhereCollision(page, name, tolerance) {
  const boxes = await page.evaluate((n) => rbview.visualAndCollisionBoxes(n), name);
  assert.ok(boxes, `${name} has no drawn visuals`);
  for (const end of ["min", "max"]) {
    for (let k = 0; k < 3; k++) {
      assert.ok(Math.abs(boxes.visual[end][k] - boxes.collision[end][k]) < tolerance,
        `${name}: its visual's box ${JSON.stringify(boxes.visual)} is not its collision shape's `
        + `${JSON.stringify(boxes.collision)}`);
    }
  }
}

test("the UR5e is drawn from its COLLADA files in their own colours", async () => {
  const { page, meshes } = await openExampleWorld("ur5e");
  try {
    const dae = meshes.filter((m) => m.url.endsWith(".dae"));
    assert.equal(dae.length, 7, JSON.stringify(meshes));
    assert.ok(dae.every((m) => m.url.startsWith("world/robots/ur5e/meshes/visual/")), JSON.stringify(dae));
    // Every one drawn from its file, not from the collision fallback.
    assert.deepEqual(await page.evaluate(() => rbview.visualMeshesDrawn()), { dae: 7 });
    assert.equal(await page.evaluate(() => rbview.viewer.noVisuals.size), 0);
    for (const body of new Set(dae.map((m) => m.body))) await assertVisualWhereCollision(page, body, 0.02);

    await hidePanels(page);
    await screenshot(page, "visuals-ur5e");
    const { png } = await screenshotWithoutJoints(page, "visuals-ur5e-no-joints");
    const rect = await page.evaluate(() => rbview.screenRect(...rbview.state.world.bodies
      .filter((b) => b.name.startsWith("ur5e/")).map((b) => b.name)));
    const region = { x: rect.left, y: rect.top, width: rect.right - rect.left, height: rect.bottom - rect.top };
    const inArm = await robotColours(page, png, region);
    const whole = await robotColours(page, png, { x: 0, y: 0, width: VIEW.width, height: VIEW.height });
    // The blue caps of its joints, the light grey of its links and the dark
    // grey of its joint housings, where the arm is and (the blue) nowhere else.
    assert.ok(inArm.urBlue > 1500, `only ${inArm.urBlue} pixels of UR blue where the arm is: ${JSON.stringify(inArm)}`);
    assert.ok(inArm.lightGrey > 1500, `only ${inArm.lightGrey} light grey pixels where the arm is: ${JSON.stringify(inArm)}`);
    assert.ok(inArm.darkGrey > 1500, `only ${inArm.darkGrey} dark grey pixels where the arm is: ${JSON.stringify(inArm)}`);
    assert.ok(inArm.urBlue >= 0.98 * whole.urBlue, `UR blue away from the arm: ${inArm.urBlue} of ${whole.urBlue}`);
    assert.deepEqual(page.errors, [], `console errors:\n${page.errors.join("\n")}\n${logs()}`);
  } finally {
    await page.close();
    stopAll();
  }
});

test("the Franka Panda is drawn from its OBJ files in white, with its fingers", async () => {
  const { page, meshes } = await openExampleWorld("panda");
  try {
    assert.ok(meshes.length >= 10 && meshes.every((m) => m.url.endsWith(".obj")), JSON.stringify(meshes));
    assert.deepEqual(await page.evaluate(() => rbview.visualMeshesDrawn()), { obj: meshes.length });
    const fingers = ["panda/panda_leftfinger", "panda/panda_rightfinger"];
    for (const finger of fingers) {
      assert.ok(meshes.some((m) => m.body === finger && m.url.endsWith("/finger.obj")), `${finger}: ${JSON.stringify(meshes)}`);
      await assertVisualWhereCollision(page, finger, 0.01);
    }
    for (const link of ["panda/panda_link1", "panda/panda_link4", "panda/panda_link7"]) { // link7 holds the hand
      await assertVisualWhereCollision(page, link, 0.02);
    }

    await hidePanels(page);
    await screenshot(page, "visuals-panda");
    const { png } = await screenshotWithoutJoints(page, "visuals-panda-no-joints");
    // The URDF's panda_white, lit: light grey where the arm is, and where each
    // finger is (the rectangle its box projects to).
    const arm = await page.evaluate(() => rbview.screenRect(...rbview.state.world.bodies
      .filter((b) => b.name.startsWith("panda/")).map((b) => b.name)));
    const inArm = await robotColours(page, png,
      { x: arm.left, y: arm.top, width: arm.right - arm.left, height: arm.bottom - arm.top });
    assert.ok(inArm.lightGrey > 5000, `only ${inArm.lightGrey} white pixels where the arm is: ${JSON.stringify(inArm)}`);
    assert.equal(inArm.urBlue, 0, "the Panda has no blue");
    for (const finger of fingers) {
      const r = await page.evaluate((n) => rbview.screenRect(n), finger);
      const at = await robotColours(page, png, { x: r.left, y: r.top, width: r.right - r.left, height: r.bottom - r.top });
      assert.ok(at.lightGrey > 0.1 * at.all, `${finger}: ${at.lightGrey} white pixels of ${at.all} where it is`);
    }
    assert.deepEqual(page.errors, [], `console errors:\n${page.errors.join("\n")}\n${logs()}`);
  } finally {
    await page.close();
    stopAll();
  }
});

// COLLADA files declare their own unit and up axis: rbview must place each in
// its link's frame as rbserver does (Z_UP kept, Y_UP and X_UP turned to z up,
// the unit applied), not as three.js's ColladaLoader would. Three one-link
// robots, each drawn from and colliding as the same COLLADA box, 0.1 × 0.2 ×
// 0.4 m from its link's origin along x, y and z, written in metres Z_UP, in
// centimetres Y_UP and in millimetres X_UP. Each is drawn where it collides.
const COLLADA_FRAMES = [
  // name, up axis, metres per unit, a link-frame point (metres) in the file's coordinates
  ["z_up_m", "Z_UP", 1, ([x, y, z]) => [x, y, z]],
  ["y_up_cm", "Y_UP", 0.01, ([x, y, z]) => [x, z, -y].map((v) => v / 0.01)],
  ["x_up_mm", "X_UP", 0.001, ([x, y, z]) => [z, -x, -y].map((v) => v / 0.001)],
];
const COLLADA_BOX = [0.1, 0.2, 0.4];

function colladaBox(up, metres, toFile) {
  const corners = [];
  for (let k = 0; k < 8; k++) {
    corners.push(toFile([k & 1 ? COLLADA_BOX[0] : 0, k & 2 ? COLLADA_BOX[1] : 0, k & 4 ? COLLADA_BOX[2] : 0]));
  }
  // Two triangles a face, counter-clockwise seen from outside (a rotation
  // into the file's axes keeps them so).
  const faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
  const triangles = faces.flatMap(([a, b, c, d]) => [a, b, c, a, c, d]);
  return `<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="u" meter="${metres}"/><up_axis>${up}</up_axis></asset>
  <library_effects><effect id="teal-effect"><profile_COMMON><technique sid="common"><lambert>
    <diffuse><color>0.1 0.7 0.6 1</color></diffuse>
  </lambert></technique></profile_COMMON></effect></library_effects>
  <library_materials><material id="teal" name="teal"><instance_effect url="#teal-effect"/></material></library_materials>
  <library_geometries><geometry id="box"><mesh>
    <source id="box-positions">
      <float_array id="box-positions-array" count="24">${corners.flat().join(" ")}</float_array>
      <technique_common><accessor source="#box-positions-array" count="8" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common>
    </source>
    <vertices id="box-vertices"><input semantic="POSITION" source="#box-positions"/></vertices>
    <triangles material="teal" count="12">
      <input semantic="VERTEX" source="#box-vertices" offset="0"/>
      <p>${triangles.join(" ")}</p>
    </triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="box-node">
    <instance_geometry url="#box"><bind_material><technique_common>
      <instance_material symbol="teal" target="#teal"/>
    </technique_common></bind_material></instance_geometry>
  </node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
`;
}

function colladaFramesWorld() {
  const dir = path.join(work, "collada_frames");
  mkdirSync(dir, { recursive: true });
  const robots = [];
  COLLADA_FRAMES.forEach(([name, up, metres, toFile], k) => {
    writeFileSync(path.join(dir, `${name}.dae`), colladaBox(up, metres, toFile));
    writeFileSync(path.join(dir, `${name}.urdf`), [
      `<robot name="${name}"><link name="box">`,
      `  <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>`,
      `  <visual><geometry><mesh filename="${name}.dae"/></geometry></visual>`,
      `  <collision><geometry><mesh filename="${name}.dae"/></geometry></collision>`,
      `</link></robot>`, ""].join("\n"));
    robots.push(`  - {name: ${name}, urdf: ${name}.urdf, fixed_base: true, position: [${0.5 * k}, 0, 0]}`);
  });
  writeFileSync(path.join(dir, "frames.yaml"), [
    "world: {dt: 0.001, gravity: [0, 0, -9.81]}",
    "lcm: {state_rate: 60, status_rate: 10}",
    "robots:", ...robots, ""].join("\n"));
  return dir;
}

test("a COLLADA file's unit and up axis place it in its link's frame as rbserver reads it", async () => {
  const dir = colladaFramesWorld();
  startProcess("rbserver", path.join(build, "server", "daemon", "rbserver"),
    ["--config", path.join(dir, "frames.yaml"), "--paused", "--log-level", "info"]);
  const url = await rbview("--meshes", dir);
  const page = await openPage(browser, url, VIEW);
  try {
    await waitForVisuals(page);
    assert.deepEqual(await page.evaluate(() => rbview.visualsFailed()), []);
    assert.deepEqual(await page.evaluate(() => rbview.visualMeshesDrawn()), { dae: COLLADA_FRAMES.length });
    for (const [k, [name]] of COLLADA_FRAMES.entries()) {
      const boxes = await page.evaluate((n) => rbview.visualAndCollisionBoxes(n), `${name}/box`);
      assert.ok(boxes, `${name}/box has no drawn visuals`);
      const expected = { min: [0.5 * k, 0, 0], max: [0.5 * k + COLLADA_BOX[0], COLLADA_BOX[1], COLLADA_BOX[2]] };
      for (const [which, box] of Object.entries(boxes)) {
        for (const end of ["min", "max"]) {
          assert.ok(box[end].every((v, i) => Math.abs(v - expected[end][i]) < 0.002),
            `${name}: its ${which} box is ${JSON.stringify(box)}, not ${JSON.stringify(expected)}`);
        }
      }
    }
    await hidePanels(page);
    await screenshot(page, "visuals-collada-frames");
    assert.deepEqual(page.errors, [], `console errors:\n${page.errors.join("\n")}\n${logs()}`);
  } finally {
    await page.close();
    stopAll();
  }
});
