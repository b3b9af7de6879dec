// The Machine view: the machine in 3-D with live inverse kinematics from pose sliders, struts
// coloured by stroke margin, joints by cone-angle margin, the closest pair and its clearance, the
// condition number on a gauge, and a second machine (e.g. the calibrated one) drawn beside it.
import { post } from "./api.js";

const fmt = (v, d = 3) => (v === null || v === undefined ? "off" : Number(v).toFixed(d));

/** Rotates unit vector u by a (about x) then b (about y), degrees. */
function tilt(u, a, b) {
  const ra = (a * Math.PI) / 180, rb = (b * Math.PI) / 180;
  const y1 = u[1] * Math.cos(ra) - u[2] * Math.sin(ra), z1 = u[1] * Math.sin(ra) + u[2] * Math.cos(ra);
  const x2 = u[0] * Math.cos(rb) + z1 * Math.sin(rb), z2 = -u[0] * Math.sin(rb) + z1 * Math.cos(rb);
  return [x2, y1, z2];
}

export class MachineView {
  constructor(root, app) {
    this.app = app;
    root.innerHTML = `
      <div class="side">
        <h3>Pose</h3><div id="pose-sliders"></div>
        <h3>Check</h3>
        <div>status <b id="pose-status">-</b></div>
        <div>condition <meter id="cond-gauge" min="1" max="100" low="30" high="70" optimum="1"></meter> <span id="cond-value"></span></div>
        <div>closest struts <span id="pose-pair"></span></div>
        <table id="pose-table"></table>
        <div id="pose-violations" class="violations"></div>
        <div id="livecal-panel"></div>
      </div>
      <div class="canvas" id="machine-canvas"></div>`;
    this.sliders = root.querySelector("#pose-sliders");
    this.pending = false;
    this.again = false;
  }

  /** Shows machine `m` (GET /api/machines/NAME) at home, and `compare` (or null) beside it. */
  show(m, compare) {
    this.m = m;
    this.compare = compare;
    const scene = this.app.scene("machine-canvas");
    scene.clear(0);
    scene.frame(m.drawing);
    this.scale = scene.size;
    const zmin = Math.min(...m.drawing.base_points.map((p) => p[2]), m.drawing.tool_point[2]);
    scene.table(Math.min(zmin, m.drawing.tool_point[2]) - this.scale * 0.05, this.scale);
    const hexapod = m.type === "hexapod";
    const names = hexapod ? ["x", "y", "z", "a", "b", "c"] : ["x", "y", "z", "tilt a", "tilt b"];
    const r = this.scale * 0.25;
    this.sliders.innerHTML = names
      .map((n, k) => {
        const home = hexapod ? m.home[k] : k < 3 ? m.home[k] : 0;
        const span = k < 3 ? r : 25;
        return `<label>${n} <input type="range" data-k="${k}" min="${home - span}" max="${home + span}" step="${span / 500}" value="${home}"><output></output></label>`;
      })
      .join("");
    for (const s of this.sliders.querySelectorAll("input")) s.addEventListener("input", () => this.update());
    this.update();
  }

  /** A record of the followed LinuxCNC: the machine where LinuxCNC says it is, its tool's trail. */
  showLive(j) {
    if (!j.check || !this.m) return;
    this.liveRow = j.check;
    this.livePose = j.status.pose_actual;
    for (const [k, s] of [...this.sliders.querySelectorAll("input")].entries()) {
      s.disabled = true;
      s.value = this.livePose[k];
      s.nextElementSibling.textContent = Number(this.livePose[k]).toFixed(k < 3 ? 3 : 2);
    }
    this.render({ rows: [j.check], units: j.machine.units, type: "hexapod", joints: this.m.joints });
    this.app.scene("machine-canvas").trail(j.check.tool_point);
  }

  /** Back to the sliders' pose. */
  endLive() {
    if (!this.liveRow) return;
    this.liveRow = null;
    for (const s of this.sliders.querySelectorAll("input")) s.disabled = false;
    this.app.scene("machine-canvas").trail(null);
    this.update();
  }

  /** The pose the sliders give, as POST /api/ik takes it. */
  pose() {
    const v = [...this.sliders.querySelectorAll("input")].map((s) => Number(s.value));
    for (const [k, s] of [...this.sliders.querySelectorAll("output")].entries()) s.textContent = v[k].toFixed(k < 3 ? 2 : 1);
    if (this.m.type === "hexapod") return v;
    return [v[0], v[1], v[2], ...tilt(this.m.home.slice(3), v[3], v[4])];
  }

  /** One IK request at a time; the newest pose wins. */
  async update() {
    if (this.pending) {
      this.again = true;
      return;
    }
    this.pending = true;
    try {
      const pose = this.pose();
      const main = await post("/api/ik", { machine: this.m.name, poses: [pose] });
      this.render(main);
      if (this.compare) {
        const other = await post("/api/ik", { machine: this.compare.name, poses: [pose] });
        if (other.rows[0].base_points.length)
          this.app.scene("machine-canvas").draw(1, other.rows[0], this.style(this.compare));
      }
    } catch (e) {
      this.app.error(e);
    } finally {
      this.pending = false;
      if (this.again) {
        this.again = false;
        this.update();
      }
    }
  }

  style(m) {
    return { scale: this.scale, diameter: m.machine.strut_diameter || 0, type: m.type, hybrid: m.machine.hybrid };
  }

  render(result) {
    const row = result.rows[0];
    const status = document.querySelector("#pose-status");
    // Every violated check, not only the first (the list below gives each).
    const kinds = [...new Set(row.violations.map((v) => v.split(/[ :]/)[0]))];
    status.textContent = row.status === "ok" || kinds.length < 2 ? row.status : `${row.status} and ${kinds.length - 1} more`;
    status.className = row.status === "ok" ? "ok" : "bad";
    if (row.base_points.length) this.app.scene("machine-canvas").draw(0, row, this.style(this.m));
    const c = row.condition_number;
    document.querySelector("#cond-gauge").value = c ?? 0;
    document.querySelector("#cond-value").textContent = `${fmt(c, 1)} (margin ${fmt(row.condition_margin, 1)})`;
    document.querySelector("#pose-pair").textContent =
      row.closest_pair[0] < 0
        ? "-"
        : row.clearance === null
          ? `${row.closest_pair[0]}-${row.closest_pair[1]} (no strut diameter: clearance not checked)`
          : `${row.closest_pair[0]}-${row.closest_pair[1]}: clearance ${fmt(row.clearance)} ${result.units}`;
    const hexapod = result.type === "hexapod";
    const rows = result.joints.map(
      (n, i) =>
        `<tr><td>${n}</td><td>${fmt(row.joints[i])}</td><td class="${row.stroke_margin[i] < 0 ? "bad" : ""}">${fmt(row.stroke_margin[i])}</td>${hexapod ? `<td class="${row.angle_margin[i] < 0 ? "bad" : ""}">${fmt(row.angle_margin[i], 2)}</td>` : ""}</tr>`,
    );
    const angles = hexapod
      ? ""
      : `<tr><td colspan="3">angle margins °: ${["alpha", "beta", "wrist C", "wrist A"].map((n, k) => `${n} ${fmt(row.angle_margin[k], 1)}`).join(", ")}</td></tr>`;
    document.querySelector("#pose-table").innerHTML =
      `<tr><th>joint</th><th>value</th><th>stroke margin</th>${hexapod ? "<th>cone margin °</th>" : ""}</tr>` + rows.join("") + angles;
    document.querySelector("#pose-violations").textContent = row.violations.join("\n");
  }
}
