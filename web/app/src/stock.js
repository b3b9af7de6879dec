// The machining preview in 3-D (docs/machining.md): the stock as a height-field surface that the
// server's frames lower as the program plays (cut cells coloured), and the cutting tool at its
// tip. Draws what POST /api/gcode/run returns under "machining"; computes nothing of its own.
import * as THREE from "three";

/** A base64 string of little-endian 32-bit values as a Float32Array or Uint32Array. */
export function decode(text, Type) {
  const bytes = Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
  return new Type(bytes.buffer);
}

const STOCK = new THREE.Color(0xc8a165); // untouched material
const CUT = new THREE.Color(0x5b8def); // machined surface
const EMPTY = new THREE.Color(0xe2e8f0); // outside a cylinder's outline

export class StockView {
  /** `scene` is a MachineScene; `toUnit` converts mm to the drawing's unit. */
  constructor(scene) {
    this.scene = scene;
    this.mesh = null;
    this.tool = null;
  }

  /** Removes the stock and the tool from the scene. */
  clear() {
    for (const o of [this.mesh, this.tool]) if (o) this.scene.scene.remove(o);
    this.mesh = this.tool = null;
    this.data = null;
    this.scene.invalidate();
  }

  /** Builds the stock of `m` (the run's "machining") at its initial state. */
  show(m, path, toUnit = 1) {
    this.clear();
    const { nx, ny, cell, x0, y0 } = m;
    this.toUnit = toUnit;
    this.initial = decode(m.initial, Float32Array);
    this.finished = decode(m.heights, Float32Array);
    this.frames = m.frames.map((f) => ({ t: f.t, cells: decode(f.cells, Uint32Array), heights: decode(f.heights, Float32Array) }));
    this.inside = this.initial.map((h) => (h > m.stock.bottom ? 1 : 0));
    this.complete = m.frames_complete;
    this.m = m;
    this.path = path;
    const positions = new Float32Array(nx * ny * 3);
    for (let j = 0; j < ny; ++j)
      for (let i = 0; i < nx; ++i) {
        const k = j * nx + i;
        positions[3 * k] = (x0 + (i + 0.5) * cell) * toUnit;
        positions[3 * k + 1] = (y0 + (j + 0.5) * cell) * toUnit;
      }
    const index = new Uint32Array(Math.max(0, (nx - 1) * (ny - 1) * 6));
    let n = 0;
    for (let j = 0; j + 1 < ny; ++j)
      for (let i = 0; i + 1 < nx; ++i) {
        const a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
        index.set([a, b, d, a, d, c], n);
        n += 6;
      }
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(positions, 3));
    g.setAttribute("color", new THREE.BufferAttribute(new Float32Array(nx * ny * 3), 3));
    g.setAttribute("normal", new THREE.BufferAttribute(new Float32Array(nx * ny * 3), 3));
    g.setIndex(new THREE.BufferAttribute(index, 1));
    this.mesh = new THREE.Mesh(g, new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide }));
    this.mesh.name = "stock";
    this.scene.scene.add(this.mesh);
    this.heights = Float32Array.from(this.initial);
    this.applied = 0; // frames applied to this.heights
    this.refresh();
    g.computeBoundingSphere(); // heights only fall: the initial stock bounds every later one
  }

  /**
   * Writes this.heights into the mesh: every cell, or only `cells` (a Set of changed cells) with
   * the normals of their neighbours. Normals by central differences of the grid.
   */
  refresh(cells = null) {
    const g = this.mesh.geometry;
    const { nx, ny, cell } = this.m;
    const pos = g.attributes.position.array, col = g.attributes.color.array, nor = g.attributes.normal.array;
    const h = this.heights;
    const setCell = (k) => {
      pos[3 * k + 2] = h[k] * this.toUnit;
      const c = !this.inside[k] ? EMPTY : h[k] < this.initial[k] - 1e-3 ? CUT : STOCK;
      col[3 * k] = c.r;
      col[3 * k + 1] = c.g;
      col[3 * k + 2] = c.b;
    };
    const setNormal = (k) => {
      const i = k % nx, j = (k - i) / nx;
      const dx = (h[j * nx + Math.min(i + 1, nx - 1)] - h[j * nx + Math.max(i - 1, 0)]) / (2 * cell);
      const dy = (h[Math.min(j + 1, ny - 1) * nx + i] - h[Math.max(j - 1, 0) * nx + i]) / (2 * cell);
      const n = 1 / Math.hypot(dx, dy, 1);
      nor[3 * k] = -dx * n;
      nor[3 * k + 1] = -dy * n;
      nor[3 * k + 2] = n;
    };
    let lo = 0, hi = h.length - 1;
    if (!cells) {
      for (let k = 0; k < h.length; ++k) setCell(k);
      for (let k = 0; k < h.length; ++k) setNormal(k);
    } else {
      if (!cells.size) return;
      lo = Infinity;
      hi = -1;
      for (const k of cells) {
        setCell(k);
        lo = Math.min(lo, k - nx);
        hi = Math.max(hi, k + nx);
      }
      lo = Math.max(lo, 0);
      hi = Math.min(hi, h.length - 1);
      for (const k of cells) for (const m of [k, k - 1, k + 1, k - nx, k + nx]) if (m >= 0 && m < h.length) setNormal(m);
    }
    for (const name of ["position", "color", "normal"]) {
      const a = g.attributes[name];
      a.clearUpdateRanges();
      a.addUpdateRange(3 * lo, 3 * (hi - lo + 1));
      a.needsUpdate = true;
    }
    this.scene.invalidate();
  }

  /** The stock as machined up to `time` (s), and the tool where it is then. */
  at(time) {
    if (!this.mesh) return;
    let target = 0;
    while (target < this.frames.length && this.frames[target].t <= time) ++target;
    if (target !== this.applied) {
      const back = target < this.applied;
      if (back) {
        this.heights.set(this.initial);
        this.applied = 0;
      }
      const changed = back ? null : new Set();
      for (; this.applied < target; ++this.applied) {
        const f = this.frames[this.applied];
        for (let k = 0; k < f.cells.length; ++k) {
          this.heights[f.cells[k]] = f.heights[k];
          if (changed) changed.add(f.cells[k]);
        }
      }
      this.refresh(changed);
    }
    this.drawTool(time);
  }

  /** Frames the camera on the stock. */
  zoom() {
    if (this.mesh) this.scene.frameBox(new THREE.Box3().setFromObject(this.mesh));
  }

  /** The finished part: every cell as the program leaves it, the tool hidden. */
  showFinished() {
    if (!this.mesh) return;
    this.heights.set(this.finished);
    this.applied = this.frames.length;
    this.refresh();
    if (this.tool) this.tool.visible = false;
  }

  /** The cutter (shank and ball or flat end) at the path point reached at `time`. */
  drawTool(time) {
    const p = this.path;
    const tips = this.m.path_tools;
    if (!tips || !tips.tip.length) return;
    let lo = 0, hi = p.t.length - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (p.t[mid] <= time) lo = mid;
      else hi = mid - 1;
    }
    const at = { tip: tips.tip[lo], axis: tips.axis[lo] };
    const tool = this.m.tools.find((t) => t.number === tips.tool[lo]) || this.m.tools[0];
    if (!tool) return;
    if (!this.tool || this.toolNumber !== tool.number) {
      if (this.tool) this.scene.scene.remove(this.tool);
      this.tool = this.toolMesh(tool);
      this.toolNumber = tool.number;
      this.scene.scene.add(this.tool);
    }
    this.tool.visible = true;
    const u = this.toUnit;
    this.tool.position.set(at.tip[0] * u, at.tip[1] * u, at.tip[2] * u);
    this.tool.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), new THREE.Vector3(...at.axis));
    this.scene.invalidate();
  }

  /** The tool in its own frame: tip at the origin, axis +z; the holder above the gauge line. */
  toolMesh(tool) {
    const u = this.toUnit;
    const r = (tool.diameter / 2) * u;
    const group = new THREE.Group();
    group.name = "cutter";
    const steel = new THREE.MeshStandardMaterial({ color: 0x9ca3af, metalness: 0.6, roughness: 0.35 });
    const start = tool.end === "ball" ? r : 0;
    const shank = new THREE.Mesh(new THREE.CylinderGeometry(r, r, tool.length * u - start, 24), steel);
    shank.rotation.x = Math.PI / 2;
    shank.position.z = start + (tool.length * u - start) / 2;
    group.add(shank);
    if (tool.end === "ball") {
      const ball = new THREE.Mesh(new THREE.SphereGeometry(r, 24, 16), steel);
      ball.position.z = r;
      group.add(ball);
    }
    const hr = (tool.holder_diameter / 2) * u;
    const holder = new THREE.Mesh(new THREE.CylinderGeometry(hr, hr, tool.holder_length * u, 32), new THREE.MeshStandardMaterial({ color: 0x374151, transparent: true, opacity: 0.45 }));
    holder.rotation.x = Math.PI / 2;
    holder.position.z = tool.length * u + (tool.holder_length * u) / 2;
    group.add(holder);
    return group;
  }
}
