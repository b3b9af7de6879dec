// The machine in 3-D (three.js): struts or legs as cylinders coloured by stroke margin, joints as
// spheres coloured by angle margin, the closest pair of struts marked, the tool, the work table,
// a programmed path; orbit, zoom and pan with the mouse. Draws what POST /api/ik returns.
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

/** Green (ample margin) through amber to red (violated): `fraction` is margin / scale. */
export function marginColour(margin, scale) {
  if (margin === null || margin === undefined) return new THREE.Color(0x8a94a6); // disabled
  if (margin < 0) return new THREE.Color(0xd7263d);
  const f = Math.min(1, margin / scale);
  return new THREE.Color().setHSL(0.02 + 0.3 * f, 0.75, 0.45);
}

const up = new THREE.Vector3(0, 1, 0);

/** A label that always faces the camera: `text` on a small white disc (strut numbers). */
function label(text) {
  const canvas = document.createElement("canvas");
  canvas.width = canvas.height = 64;
  const c = canvas.getContext("2d");
  c.fillStyle = "rgba(255,255,255,0.85)";
  c.beginPath();
  c.arc(32, 32, 26, 0, 2 * Math.PI);
  c.fill();
  c.fillStyle = "#111827";
  c.font = "bold 36px sans-serif";
  c.textAlign = "center";
  c.textBaseline = "middle";
  c.fillText(text, 32, 34);
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(canvas), depthTest: false }));
  sprite.renderOrder = 10;
  return sprite;
}

/** A cylinder of radius r between a and b (THREE.Vector3). */
function placeCylinder(mesh, a, b, r) {
  const d = new THREE.Vector3().subVectors(b, a);
  const len = Math.max(d.length(), 1e-9);
  mesh.scale.set(r, len, r);
  mesh.position.copy(a).addScaledVector(d, 0.5);
  mesh.quaternion.setFromUnitVectors(up, d.normalize());
}

export class MachineScene {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setClearColor(0xf7f8fa);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.1, 1e6);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.zoomSpeed = 0.3; // a wheel notch zooms by about 6 %, not by half
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 2.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.5);
    sun.position.set(1, -2, 3);
    this.scene.add(sun);
    this.groups = [];
    this.path = null;
    this.marker = null;
    new ResizeObserver(() => this.resize()).observe(container);
    this.controls.addEventListener("change", () => this.invalidate());
    this.resize();
  }

  /** Renders at the next animation frame (once, however often it is called before). */
  invalidate() {
    if (this.queued) return;
    this.queued = true;
    requestAnimationFrame(() => {
      this.queued = false;
      if (this.container.clientWidth === 0) return; // hidden view: drawn when shown
      this.renderer.render(this.scene, this.camera);
    });
  }

  resize() {
    const w = this.container.clientWidth || 400;
    const h = this.container.clientHeight || 300;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.invalidate();
  }

  /** Frames the camera on the points of a drawing. */
  frame(drawing) {
    const box = new THREE.Box3();
    for (const p of [...drawing.base_points, ...drawing.moving_points, drawing.tool_point])
      box.expandByPoint(new THREE.Vector3(...p));
    this.frameBox(box, false);
  }

  /** Frames the camera on a THREE.Box3; `keepSize`: the margin colours' scale stays. */
  frameBox(box, keepSize = true) {
    const centre = box.getCenter(new THREE.Vector3());
    const size = Math.max(box.getSize(new THREE.Vector3()).length(), 1);
    if (!keepSize) this.size = size;
    this.camera.position.set(centre.x + size * 1.2, centre.y - size * 1.6, centre.z + size * 0.9);
    this.camera.near = size / 1000;
    this.camera.far = size * 100;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(centre);
    this.controls.update();
    this.invalidate();
  }

  /**
   * Draws machine `index` (0: the machine, 1: the comparison, drawn translucent) from a row of
   * POST /api/ik. `scale` is the machine's size (for margin colours), `diameter` the strut's.
   */
  draw(index, row, { scale, diameter, type, hybrid }) {
    let g = this.groups[index];
    if (!g) {
      g = this.groups[index] = { root: new THREE.Group(), struts: [], joints: [], extra: [] };
      this.scene.add(g.root);
    }
    const translucent = index > 0;
    const n = row.base_points.length;
    const radius = (diameter > 0 ? diameter : scale * 0.02) / 2;
    const geometry = new THREE.CylinderGeometry(1, 1, 1, 20);
    const ball = new THREE.SphereGeometry(1, 16, 12);
    g.labels = g.labels || [];
    while (g.struts.length < n) {
      const m = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({ transparent: translucent, opacity: translucent ? 0.35 : 1 }));
      g.root.add(m);
      g.struts.push(m);
      if (!translucent) {
        const l = label(String(g.struts.length - 1)); // the struts' numbers, as the checks name them
        g.root.add(l);
        g.labels.push(l);
      }
      for (let k = 0; k < 2; ++k) {
        const j = new THREE.Mesh(ball, new THREE.MeshStandardMaterial({ transparent: translucent, opacity: translucent ? 0.35 : 1 }));
        g.root.add(j);
        g.joints.push(j);
      }
    }
    for (const e of g.extra) g.root.remove(e);
    g.extra = [];
    const solved = row.base_points.length > 0;
    for (let i = 0; i < n; ++i) {
      const a = new THREE.Vector3(...row.base_points[i]);
      const b = new THREE.Vector3(...row.moving_points[i]);
      placeCylinder(g.struts[i], a, b, radius);
      const pair = row.closest_pair.includes(i) && row.clearance !== null && row.clearance < radius * 2;
      // A violated stroke stays red; the closest pair is purple only where that hides nothing.
      const violated = row.stroke_margin[i] !== null && row.stroke_margin[i] < 0;
      g.struts[i].material.color = pair && !violated ? new THREE.Color(0x7b2cbf) : marginColour(row.stroke_margin[i], scale * 0.05);
      if (g.labels[i]) {
        g.labels[i].position.copy(a).lerp(b, 0.55);
        g.labels[i].scale.setScalar(Math.max(radius * 3, scale * 0.022));
      }
      const am = type === "hexapod" ? row.angle_margin[i] : null;
      for (const [k, p] of [[0, a], [1, b]]) {
        const j = g.joints[2 * i + k];
        j.position.copy(p);
        j.scale.setScalar(radius * 1.6);
        j.material.color = marginColour(am, 10);
      }
    }
    this.invalidate();
    if (!solved) return;
    const polygon = (pts, colour) => {
      const shape = new THREE.BufferGeometry().setFromPoints([...pts, pts[0]].map((p) => new THREE.Vector3(...p)));
      const line = new THREE.Line(shape, new THREE.LineBasicMaterial({ color: colour, transparent: translucent, opacity: translucent ? 0.4 : 1 }));
      g.root.add(line);
      g.extra.push(line);
    };
    polygon(row.base_points, 0x334155);
    polygon(row.moving_points, 0x1d4ed8);
    const tip = new THREE.Vector3(...row.tool_point);
    const dir = new THREE.Vector3(...row.tool_direction);
    const tool = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({ color: 0x111827, transparent: translucent, opacity: translucent ? 0.35 : 1 }));
    placeCylinder(tool, tip, tip.clone().addScaledVector(dir, scale * 0.12), radius * 0.6);
    g.root.add(tool);
    g.extra.push(tool);
    if (row.carriage && row.carriage.length === 2 && hybrid) this.drawCarriage(g, row, hybrid, scale, translucent);
    for (const w of row.wrist_points || []) {
      const s = new THREE.Mesh(ball, new THREE.MeshStandardMaterial({ color: 0xf59e0b }));
      s.position.set(...w);
      s.scale.setScalar(radius * 2.2);
      g.root.add(s);
      g.extra.push(s);
      const axis = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({ color: 0x92400e }));
      placeCylinder(axis, s.position, tip, radius * 0.9);
      g.root.add(axis);
      g.extra.push(axis);
    }
  }

  /**
   * A hybrid machine's serial axes, in the PKM's frame P (which X2 carries): the X2 rail over its
   * stroke (it moves by −x2 relative to P), the carriage holding the PKM's base, and the Y2 work
   * table under the tool, shifted by y2 along y.
   */
  drawCarriage(g, row, hybrid, scale, translucent) {
    const [x2, y2] = row.carriage;
    const box = (size, centre, colour) => {
      const m = new THREE.Mesh(new THREE.BoxGeometry(...size), new THREE.MeshStandardMaterial({ color: colour, transparent: true, opacity: translucent ? 0.2 : 0.55 }));
      m.position.set(...centre);
      g.root.add(m);
      g.extra.push(m);
    };
    const zs = row.base_points.map((p) => p[2]);
    const xs = row.base_points.map((p) => p[0]);
    const ys = row.base_points.map((p) => p[1]);
    const top = Math.max(...zs) + scale * 0.04;
    const [x0, x1] = hybrid.x2_stroke;
    const width = Math.max(...ys) - Math.min(...ys) + scale * 0.1;
    const yc = (Math.max(...ys) + Math.min(...ys)) / 2;
    // The rail: the whole X2 stroke plus the carriage's length, fixed in the world.
    const length = Math.max(...xs) - Math.min(...xs) + scale * 0.1;
    box([x1 - x0 + length, width * 0.3, scale * 0.03], [(x0 + x1) / 2 - x2, yc, top + scale * 0.05], 0x64748b);
    box([length, width, scale * 0.04], [(Math.max(...xs) + Math.min(...xs)) / 2, yc, top], 0xf59e0b);
    // The Y2 table, below the tool.
    const [y0, y1] = hybrid.y2_stroke;
    const tz = Math.min(row.tool_point[2], ...row.moving_points.map((p) => p[2])) - scale * 0.08;
    const pkmSize = Math.max(hybrid.pkm_max[0] - hybrid.pkm_min[0], scale * 0.3);
    box([pkmSize, pkmSize, scale * 0.03], [row.tool_point[0], y2 + (y1 + y0) / 2 * 0 + row.tool_point[1], tz], 0x0ea5e9);
    box([pkmSize * 0.2, y1 - y0 + pkmSize, scale * 0.015], [row.tool_point[0], row.tool_point[1] + y2 - (y0 + y1) / 2, tz - scale * 0.03], 0x64748b);
  }

  /** Removes comparison drawings from `index` on. */
  clear(from) {
    for (let i = from; i < this.groups.length; ++i) if (this.groups[i]) this.scene.remove(this.groups[i].root);
    this.groups.length = Math.min(this.groups.length, from);
    this.invalidate();
  }

  /** The work table: a square under the machine at height z. */
  table(z, size) {
    if (this.tableMesh) this.scene.remove(this.tableMesh);
    const grid = new THREE.GridHelper(size, 10, 0x94a3b8, 0xcbd5e1);
    grid.rotation.x = Math.PI / 2;
    grid.position.z = z;
    this.tableMesh = grid;
    this.scene.add(grid);
    this.invalidate();
  }

  /** Adds `point` to the tool's trail (at most TRAIL points, the oldest dropped); null clears it. */
  trail(point) {
    const TRAIL = 5000;
    if (!point) {
      if (this.trailLine) this.scene.remove(this.trailLine);
      this.trailLine = null;
      this.trailPoints = [];
      return this.invalidate();
    }
    this.trailPoints = this.trailPoints || [];
    const last = this.trailPoints.at(-1);
    if (last && last[0] === point[0] && last[1] === point[1] && last[2] === point[2]) return;
    this.trailPoints.push(point);
    if (this.trailPoints.length > TRAIL) this.trailPoints.shift();
    if (this.trailLine) this.scene.remove(this.trailLine);
    const geometry = new THREE.BufferGeometry().setFromPoints(this.trailPoints.map((p) => new THREE.Vector3(...p)));
    this.trailLine = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: 0xf97316 }));
    this.scene.add(this.trailLine);
    this.invalidate();
  }

  /** A programmed path (points in the machine unit) and a marker for the animation. */
  showPath(points) {
    if (this.path) this.scene.remove(this.path);
    const geometry = new THREE.BufferGeometry().setFromPoints(points.map((p) => new THREE.Vector3(...p)));
    this.path = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: 0x0ea5e9 }));
    this.scene.add(this.path);
    this.invalidate();
  }
}
