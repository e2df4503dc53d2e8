// Shared by the browser tests: rbserver and rbview as child processes (inside
// the test's private network namespace), Debian's chromium through
// playwright-core, console errors collected, screenshots kept as artefacts,
// and pixel measurements of screenshots (decoded by the browser itself).
import { spawn } from "node:child_process";
import { mkdirSync, existsSync, readFileSync, rmSync, writeFileSync, openSync } from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";
import { createRequire } from "node:module";

const here = path.dirname(fileURLToPath(import.meta.url));
export const repo = path.resolve(here, "..", "..");
const require = createRequire(path.join(repo, "clients", "web", "package.json"));
const { chromium } = require("playwright-core");

export const build = path.resolve(process.env.RBSIM_BUILD_DIR || path.join(repo, "build"));
export const artifacts = process.env.RBVIEW_ARTIFACTS || path.join(build, "tests", "web", "artifacts");
const work = process.env.RBVIEW_WORK || path.join(build, "tests", "web", "work", "browser");
export const world = path.join(here, "worlds", "viewer.yaml");
mkdirSync(artifacts, { recursive: true });
mkdirSync(work, { recursive: true });
if (process.env.RBSIM_PRIVATE_NETWORK !== "1") {
  throw new Error("the browser tests start servers on the LCM bus: run them through tests/tools/in_private_network.sh with RBSIM_PRIVATE_NETWORK=1 (ctest does)");
}

const children = [];
// A test or benchmark that dies must not leave servers running.
process.on("exit", () => stopAll());
for (const signal of ["SIGINT", "SIGTERM"]) process.on(signal, () => process.exit(1));
process.on("uncaughtException", (error) => { console.error(error); process.exit(1); });
export function startProcess(name, command, args) {
  const logPath = path.join(work, `${name}-${children.length}.log`);
  const log = openSync(logPath, "w");
  const child = spawn(command, args, { stdio: ["ignore", log, log], env: { ...process.env, RBSIM_BUILD_DIR: build } });
  children.push({ name, child, logPath });
  return child;
}

// The pid of the newest child started under `name` (rbview's launcher execs python: same pid).
export function childPid(name) {
  return children.filter((c) => c.name === name).at(-1).child.pid;
}

export function stopAll() {
  for (const { child } of [...children].reverse()) if (child.exitCode === null && child.signalCode === null) child.kill("SIGTERM");
}

export function logs() {
  return children.map(({ name, logPath }) => `---- ${name}\n${readFileSync(logPath, "utf8").slice(-3000)}`).join("\n");
}

export const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

export function rbserver(...args) {
  return startProcess("rbserver", path.join(build, "server", "daemon", "rbserver"),
    ["--config", world, "--log-level", "info", ...args]);
}

// Starts rbview on a free port; resolves with the page's URL once it listens.
export async function rbview(...args) {
  const portFile = path.join(work, `rbview-port-${children.length}`);
  rmSync(portFile, { force: true });
  const child = startProcess("rbview", path.join(repo, "clients", "web", "rbview"),
    ["--port", "0", "--port-file", portFile, ...args]);
  for (let i = 0; i < 400 && !existsSync(portFile); i++) {
    if (child.exitCode !== null) throw new Error(`rbview exited with ${child.exitCode}\n${logs()}`);
    await sleep(50);
  }
  const port = Number(readFileSync(portFile, "utf8"));
  return `http://127.0.0.1:${port}/`;
}

// Runs a Python helper to completion: {code, stdout}.
export function runPython(script, args) {
  return new Promise((resolve) => {
    const child = spawn("/usr/bin/python3", [path.join(here, script), ...args], {
      stdio: ["ignore", "pipe", "inherit"], env: { ...process.env, RBSIM_BUILD_DIR: build } });
    let stdout = "";
    const waiters = [];
    child.stdout.on("data", (d) => {
      stdout += d;
      for (const w of waiters.splice(0)) w();
    });
    const done = new Promise((r) => child.on("exit", (code) => r({ code, stdout })));
    resolve({
      done,
      // Resolves once the helper printed a line containing `text`.
      async printed(text) {
        while (!stdout.includes(text)) await new Promise((r) => waiters.push(r));
      },
    });
  });
}

export async function launchBrowser() {
  return chromium.launch({
    executablePath: process.env.RBVIEW_CHROMIUM || "/usr/bin/chromium",
    // No GPU here: WebGL through SwiftShader. No sandbox: CI runs as root.
    // RBVIEW_CHROMIUM_ARGS adds flags (space-separated), e.g. for the benchmark.
    args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--no-sandbox", "--disable-dev-shm-usage",
      ...(process.env.RBVIEW_CHROMIUM_ARGS || "").split(" ").filter(Boolean)],
  });
}

// A page with its console errors (and uncaught exceptions) collected in page.errors.
export async function openPage(browser, url, viewport = { width: 1000, height: 700 }) {
  const page = await browser.newPage({ viewport });
  page.errors = [];
  page.on("console", (m) => { if (m.type() === "error") page.errors.push(`console: ${m.text()}`); });
  page.on("pageerror", (e) => page.errors.push(`page error: ${e.message}`));
  await page.goto(url);
  await page.waitForFunction(() => window.rbview && rbview.state.world && rbview.state.frame
    && rbview.viewer.frameDrawn, null, { timeout: 20000 });
  return page;
}

export async function screenshot(page, name) {
  const file = path.join(artifacts, `${name}.png`);
  const png = await page.screenshot({ path: file });
  return { file, png };
}

// Where in `region` ({x, y, width, height}, px) a screenshot differs from the
// scene's background colour: {count, cx, cy} (centroid of those pixels).
export async function foreground(page, png, region) {
  return page.evaluate(async ({ data, region: r }) => {
    const image = new Image();
    image.src = `data:image/png;base64,${data}`;
    await image.decode();
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext("2d");
    context.drawImage(image, 0, 0);
    const pixels = context.getImageData(r.x, r.y, r.width, r.height).data;
    const background = [0x1d, 0x22, 0x30];
    let count = 0, sx = 0, sy = 0;
    for (let y = 0; y < r.height; y++) {
      for (let x = 0; x < r.width; x++) {
        const o = 4 * (y * r.width + x);
        const d = Math.abs(pixels[o] - background[0]) + Math.abs(pixels[o + 1] - background[1]) + Math.abs(pixels[o + 2] - background[2]);
        if (d > 60) { count++; sx += x; sy += y; }
      }
    }
    return { count, cx: count ? r.x + sx / count : NaN, cy: count ? r.y + sy / count : NaN };
  }, { data: png.toString("base64"), region });
}

// The box around the pixels of a screenshot that are coloured like the bodies:
// {count, left, top, right, bottom} (px). Dynamic bodies are drawn in
// saturated hues (clients/web/src/scene.js, bodyColor); the background, the
// ground plane, its grid and static bodies are greys, whose channels differ by
// less than `minChroma` (of 255) however they are lit. Hide the panels first
// (their text is coloured too): hidePanels().
export async function colouredBounds(page, png, minChroma = 40) {
  return page.evaluate(async ({ data, minChroma: min }) => {
    const image = new Image();
    image.src = `data:image/png;base64,${data}`;
    await image.decode();
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext("2d");
    context.drawImage(image, 0, 0);
    const pixels = context.getImageData(0, 0, image.width, image.height).data;
    const box = { count: 0, left: Infinity, top: Infinity, right: -Infinity, bottom: -Infinity };
    for (let y = 0; y < image.height; y++) {
      for (let x = 0; x < image.width; x++) {
        const o = 4 * (y * image.width + x);
        const r = pixels[o], g = pixels[o + 1], b = pixels[o + 2];
        if (Math.max(r, g, b) - Math.min(r, g, b) < min) continue;
        box.count++;
        box.left = Math.min(box.left, x);
        box.right = Math.max(box.right, x);
        box.top = Math.min(box.top, y);
        box.bottom = Math.max(box.bottom, y);
      }
    }
    return box;
  }, { data: png.toString("base64"), minChroma });
}

// How many pixels of `region` ({x, y, width, height}, px) of a screenshot have
// one of `colours` (0xRRGGBB), each channel within `tolerance`.
export async function countColours(page, png, region, colours, tolerance = 4) {
  return page.evaluate(async ({ data, region: r, colours: wanted, tolerance: t }) => {
    const image = new Image();
    image.src = `data:image/png;base64,${data}`;
    await image.decode();
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext("2d");
    context.drawImage(image, 0, 0);
    const pixels = context.getImageData(r.x, r.y, r.width, r.height).data;
    const rgb = wanted.map((c) => [(c >> 16) & 255, (c >> 8) & 255, c & 255]);
    let count = 0;
    for (let o = 0; o < pixels.length; o += 4) {
      if (rgb.some(([cr, cg, cb]) => Math.abs(pixels[o] - cr) <= t && Math.abs(pixels[o + 1] - cg) <= t
        && Math.abs(pixels[o + 2] - cb) <= t)) count++;
    }
    return count;
  }, { data: png.toString("base64"), region, colours, tolerance });
}

// Hides (or shows again) the HUD, the controls and the other panels.
export function hidePanels(page, hidden = true) {
  return page.evaluate((h) => {
    for (const panel of document.querySelectorAll(".panel")) panel.style.visibility = h ? "hidden" : "";
  }, hidden);
}

export function writeArtifact(name, text) {
  writeFileSync(path.join(artifacts, name), text);
}

// Clicks a control button and waits for the message line to report its ack.
export async function act(page, buttonId) {
  await page.evaluate(() => { document.getElementById("message").textContent = ""; });
  await page.click(`#${buttonId}`);
  await waitForAck(page);
  return page.locator("#message").textContent();
}

// Waits for the message line to show an ack (accepted or rejected); returns it.
export async function waitForAck(page) {
  await page.waitForFunction(() => {
    const text = document.getElementById("message").textContent;
    return / (accepted|rejected)/.test(text);
  }, null, { timeout: 30000 });
  return page.locator("#message").textContent();
}

export async function hudStep(page) {
  return Number(await page.locator("#hud-step").textContent());
}

// The HUD writes a state's step at most every 100 ms (clients/web/src/main.js):
// waits up to 1 s for it to show `step`, then returns what it shows.
export async function hudStepOnceShown(page, step) {
  await page.waitForFunction((s) => Number(document.getElementById("hud-step").textContent) === s, step,
    { timeout: 1000 }).catch(() => {});
  return hudStep(page);
}
