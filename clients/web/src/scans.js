// The beams of one range sensor or lidar (the world file's sensors:), as the
// bridge sends them (rbview_bridge/scans.py): a line from the sensor's origin
// to each hit and a dot at the hit, every k-th beam of the newest scan. The
// page lists the sensors heard in a menu; "none" draws nothing.
import * as THREE from "three";

const MAX_BEAMS = 4096; // more than the bridge sends (2048)

export class ScansView {
  constructor(scene) {
    const lines = new THREE.BufferGeometry();
    lines.setAttribute("position", new THREE.BufferAttribute(new Float32Array(MAX_BEAMS * 6), 3));
    this.rays = new THREE.LineSegments(lines, new THREE.LineBasicMaterial({ color: 0x4fc3f7, transparent: true, opacity: 0.35 }));
    const points = new THREE.BufferGeometry();
    points.setAttribute("position", new THREE.BufferAttribute(new Float32Array(MAX_BEAMS * 3), 3));
    this.hits = new THREE.Points(points, new THREE.PointsMaterial({ color: 0xff7043, size: 4, sizeAttenuation: false }));
    for (const o of [this.rays, this.hits]) {
      o.frustumCulled = false;
      o.visible = false;
      scene.add(o);
    }
    this.selected = ""; // a sensor's name, or "" for none
    this.latest = new Map(); // name -> scan
    this.drawnScan = null;
  }

  // The bridge's {type: "scans", scans: [...]}: the newest scan of every range sensor heard.
  set(message) {
    for (const scan of message.scans) this.latest.set(scan.name, scan);
    this.update();
  }

  names() {
    return [...this.latest.keys()].sort();
  }

  select(name) {
    this.selected = name;
    this.update();
  }

  update() {
    const scan = this.selected ? this.latest.get(this.selected) : null;
    this.rays.visible = this.hits.visible = !!scan;
    if (!scan || scan === this.drawnScan) return;
    this.drawnScan = scan;
    const n = Math.min(scan.hits.length / 3, MAX_BEAMS);
    const [ox, oy, oz] = scan.origin;
    const lines = this.rays.geometry.attributes.position;
    const points = this.hits.geometry.attributes.position;
    for (let i = 0; i < n; i++) {
      const x = scan.hits[3 * i], y = scan.hits[3 * i + 1], z = scan.hits[3 * i + 2];
      lines.array.set([ox, oy, oz, x, y, z], 6 * i);
      points.array.set([x, y, z], 3 * i);
    }
    lines.needsUpdate = points.needsUpdate = true;
    this.rays.geometry.setDrawRange(0, 2 * n);
    this.hits.geometry.setDrawRange(0, n);
  }
}
