// rbview benchmark: 2000 free spheres (bench/worlds/large_2000.yaml), state at
// 60 Hz, drawn in headless chromium (SwiftShader: no GPU here). Measures over
// SECONDS (default 20): frames drawn per second, new states drawn per second,
// latency from rbserver publishing a step (world_state_t.utime) to the page
// having drawn it (p50, p99), and the CPU use of the bridge (and of rbserver,
// for scale) from /proc. Run through run_viewer_bench.sh (private network).
import { readFileSync, writeFileSync } from "node:fs";
import path from "node:path";
import {
  repo, startProcess, childPid, rbview, launchBrowser, openPage, screenshot, sleep, stopAll, artifacts, build,
} from "../../../tests/web/browser_support.mjs";

const seconds = Number(process.env.SECONDS_TO_MEASURE || 20);
const width = Number(process.env.VIEW_WIDTH || 800);
const height = Number(process.env.VIEW_HEIGHT || 600);
const world = path.join(repo, "bench", "worlds", "large_2000.yaml");

function cpuSeconds(pid) {
  const fields = readFileSync(`/proc/${pid}/stat`, "utf8").split(") ")[1].split(" ");
  return (Number(fields[11]) + Number(fields[12])) / 100; // utime + stime, in USER_HZ = 100
}

const percentile = (sorted, p) => sorted[Math.min(sorted.length - 1, Math.floor(sorted.length * p))];

const server = startProcess("rbserver", path.join(build, "server", "daemon", "rbserver"),
  ["--config", world, "--state-rate", "60", "--log-level", "warning"]);
const url = await rbview();
const bridgePid = childPid("rbview");
const browser = await launchBrowser();
const page = await openPage(browser, url, { width, height });
await page.evaluate(() => rbview.lookAt([6, 6, 1], [-8, -10, 12]));
await sleep(3000); // warm up: shaders, first frames

await page.evaluate(() => { rbview.state.latencies.length = 0; rbview.state.bench = { renders: 0, fresh: 0, t0: performance.now() }; });
const bridge0 = cpuSeconds(bridgePid), server0 = cpuSeconds(server.pid), wall0 = Date.now();
const counts0 = await page.evaluate(() => ({ frames: rbview.state.framesReceived }));
const renders0 = await page.evaluate(() => rbview.state.renders || 0);
await sleep(seconds * 1000);
const bridge1 = cpuSeconds(bridgePid), server1 = cpuSeconds(server.pid), wall1 = Date.now();
const result = await page.evaluate(() => ({
  renders: rbview.state.renders, frames: rbview.state.framesReceived, drawn: rbview.state.statesDrawn,
  latencies: rbview.state.latencies.slice(), bodies: rbview.state.frame.numBodies,
}));
await screenshot(page, "bench-2000");
const wall = (wall1 - wall0) / 1000;
const latencies = result.latencies.sort((a, b) => a - b);
const report = {
  bodies: result.bodies,
  seconds: wall,
  viewport: `${width}x${height}`,
  frames_drawn_per_s: (result.renders - renders0) / wall,
  states_received_per_s: (result.frames - counts0.frames) / wall,
  states_drawn_per_s: latencies.length / wall,
  latency_ms_p50: percentile(latencies, 0.5),
  latency_ms_p99: percentile(latencies, 0.99),
  bridge_cpu_percent_of_a_core: (100 * (bridge1 - bridge0)) / wall,
  rbserver_cpu_percent_of_a_core: (100 * (server1 - server0)) / wall,
};
console.log(JSON.stringify(report, null, 2));
writeFileSync(path.join(artifacts, "bench-2000.json"), JSON.stringify(report, null, 2));
await browser.close();
stopAll();
