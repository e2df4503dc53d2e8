// Live plots of the selected body: position, velocity, energy against sim time (uPlot).
import uPlot from "uplot";
import "uplot/dist/uPlot.min.css";

const WINDOW = 10; // s of simulated time shown
const MAX_POINTS = 1200;
const AXES = [{ stroke: "#ccc", grid: { stroke: "#333" } }, { stroke: "#ccc", grid: { stroke: "#333" } }];

function chart(container, title, labels, colors) {
  const series = [{ label: "t (s)" }, ...labels.map((label, i) => ({ label, stroke: colors[i], width: 1.5 }))];
  return new uPlot({ title, width: 340, height: 100, series, axes: AXES, scales: { x: { time: false } },
    legend: { show: false } }, [[], ...labels.map(() => [])], container);
}

export class Plots {
  constructor(container) {
    this.container = container;
    this.charts = null;
    this.body = -1;
    this.lastDraw = 0;
  }

  ensureCharts() {
    if (this.charts) return;
    const rgb = ["#ff6b6b", "#51cf66", "#4dabf7"];
    this.charts = {
      position: chart(this.container, "position (m)", ["x", "y", "z"], rgb),
      velocity: chart(this.container, "velocity (m/s)", ["vx", "vy", "vz"], rgb),
      energy: chart(this.container, "energy (J)", ["kinetic", "potential", "total"], ["#ffd43b", "#9775fa", "#ffffff"]),
    };
  }

  select(body) {
    this.body = body;
    this.data = { t: [], position: [[], [], []], velocity: [[], [], []], energy: [[], [], []] };
  }

  // One state: append the selected body's values (energy from mass, principal inertia and gravity).
  add(frame, description, gravity) {
    if (this.body < 0 || !description || this.body >= frame.numBodies) return;
    const d = this.data;
    if (d.t.length && frame.simTime < d.t[d.t.length - 1]) this.select(this.body); // reset or seek back
    const p = frame.poses;
    const v = frame.velocities;
    const o = 7 * this.body;
    const u = 6 * this.body;
    d.t.push(frame.simTime);
    for (let k = 0; k < 3; k++) {
      d.position[k].push(p[o + k]);
      d.velocity[k].push(v[u + k]);
    }
    const [w, x, y, z] = [p[o + 3], p[o + 4], p[o + 5], p[o + 6]];
    const omega = [v[u + 3], v[u + 4], v[u + 5]];
    // Body-frame angular velocity R^T w, R from the principal-axes orientation q.
    const r = [
      [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
      [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
      [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ];
    let rotational = 0;
    for (let i = 0; i < 3; i++) {
      const wb = r[0][i] * omega[0] + r[1][i] * omega[1] + r[2][i] * omega[2];
      rotational += 0.5 * description.inertia[i] * wb * wb;
    }
    const m = description.mass;
    const speed2 = v[u] * v[u] + v[u + 1] * v[u + 1] + v[u + 2] * v[u + 2];
    const kinetic = 0.5 * m * speed2 + rotational;
    const potential = -m * (gravity[0] * p[o] + gravity[1] * p[o + 1] + gravity[2] * p[o + 2]);
    d.energy[0].push(kinetic);
    d.energy[1].push(potential);
    d.energy[2].push(kinetic + potential);
    let drop = 0;
    while (drop < d.t.length && (d.t[d.t.length - 1] - d.t[drop] > WINDOW || d.t.length - drop > MAX_POINTS)) drop++;
    if (drop) {
      d.t.splice(0, drop);
      for (const key of ["position", "velocity", "energy"]) for (const s of d[key]) s.splice(0, drop);
    }
  }

  draw() {
    if (this.body < 0 || this.container.classList.contains("hidden")) return;
    const now = performance.now();
    if (now - this.lastDraw < 100) return; // 10 Hz is plenty for a chart
    this.lastDraw = now;
    this.ensureCharts();
    for (const key of ["position", "velocity", "energy"]) this.charts[key].setData([this.data.t, ...this.data[key]]);
  }
}
