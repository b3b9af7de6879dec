// The Program view: a G-code editor (CodeMirror 6) with Run: the path drawn in 3-D, the machine
// animated along it (play, pause, speed, scrub), joint positions and velocities against time
// (uPlot) with their limits, every violation listed; a click on one selects its line and jumps to
// its moment. Errors show at their line.
import { EditorView, basicSetup } from "codemirror";
import { EditorSelection, StateEffect, StateField } from "@codemirror/state";
import { Decoration } from "@codemirror/view";
import uPlot from "uplot";
import "uplot/dist/uPlot.min.css";
import { gcodeLanguage } from "./gcode_mode.js";
import { get, post } from "./api.js";
import { StockView } from "./stock.js";

/** A set of line decorations that `effect` replaces (an error's line, the executing line). */
function lineField(effect) {
  return StateField.define({
    create: () => Decoration.none,
    update(marks, tr) {
      marks = marks.map(tr.changes);
      for (const e of tr.effects) if (e.is(effect)) marks = e.value;
      return marks;
    },
    provide: (f) => EditorView.decorations.from(f),
  });
}
const markLine = StateEffect.define();
const lineMarks = lineField(markLine);
const badLine = Decoration.line({ class: "cm-bad-line" });
// The line the followed LinuxCNC executes (live.js).
const markLive = StateEffect.define();
const liveMarks = lineField(markLive);
const liveLine = Decoration.line({ class: "cm-live-line" });

export const EXAMPLE = `(a square and a circle at z 200)
G21 G90 G17
G0 X0 Y0 Z200
G1 X40 F600
G1 Y40
G1 X0
G1 Y0
G2 X0 Y0 I20 J20
M2
`;

/**
 * One entry per line and check: the violated point with the smallest margin, and how many points
 * of that line violate the check; in line order.
 */
export function groupViolations(violations) {
  const groups = new Map();
  for (const v of violations) {
    const key = `${v.line} ${v.check}`;
    const g = groups.get(key);
    if (!g) groups.set(key, { ...v, count: 1 });
    else {
      g.count += 1;
      if (v.margin !== null && (g.margin === null || v.margin < g.margin)) Object.assign(g, v, { count: g.count });
    }
  }
  return [...groups.values()].sort((a, b) => a.line - b.line || a.check.localeCompare(b.check));
}

/** The simulator of one program on one machine; also used by the Blocks view. */
export class Simulator {
  constructor(root, app, canvasId, { onLine } = {}) {
    this.app = app;
    this.canvasId = canvasId;
    this.onLine = onLine;
    root.innerHTML = `
      <div class="controls">
        <button class="stop" disabled title="stop the running check">■ stop</button>
        <button class="play">▶ play</button>
        <select class="speed"><option>0.25</option><option>0.5</option><option selected>1</option><option>2</option><option>5</option><option>20</option></select>×
        <input class="scrub" type="range" min="0" max="1" step="any" value="0">
        <span class="clock">0.00 s</span>
        <span class="busy"></span>
      </div>
      <div class="machining" title="material removed as the program plays, with rapids, holder, platform and table checked against the stock (docs/machining.md)">
        <label><input type="checkbox" class="mach-on"> machining preview</label>
        <select class="mach-stock">
          <option value="auto">stock from the program</option>
          <option value="box">box X0,Y0,Z0,X1,Y1,Z1</option>
          <option value="cylinder">cylinder CX,CY,R,Z0,Z1</option>
        </select>
        <input class="mach-dims" placeholder="mm, comma-separated" size="20" disabled>
        <button class="mach-zoom" disabled title="frame the camera on the stock (the mouse wheel zooms back out)">zoom to stock</button>
        <button class="mach-part" disabled title="the part as the program leaves it, without the machine">finished part</button>
      </div>
      <div class="summary"></div>
      <div class="plots"></div>
      <ol class="violations"></ol>`;
    this.root = root;
    this.playing = false;
    root.querySelector(".play").addEventListener("click", () => this.toggle());
    root.querySelector(".stop").addEventListener("click", () => {
      if (this.job) post(`/api/jobs/${this.job}/cancel`, {}).catch(() => {});
    });
    root.querySelector(".scrub").addEventListener("input", (e) => this.seek(Number(e.target.value)));
    const kind = root.querySelector(".mach-stock");
    kind.addEventListener("change", () => (root.querySelector(".mach-dims").disabled = kind.value === "auto"));
    root.querySelector(".mach-part").addEventListener("click", () => this.showFinished());
    root.querySelector(".mach-zoom").addEventListener("click", () => this.stockView && this.stockView.zoom());
  }

  /** The request's "machining" object from the controls, or null when the preview is off. */
  machiningRequest() {
    if (!this.root.querySelector(".mach-on").checked) return null;
    const stock = this.root.querySelector(".mach-stock").value;
    // 200 cells along the stock's longer side (40,000 on a square): 12 frames/s even in software GL.
    const q = { stock, frames: 200, auto_cells: 200 };
    if (stock !== "auto") {
      const text = this.root.querySelector(".mach-dims").value.trim();
      q[stock] = text ? text.split(/[\s,]+/).map(Number) : [];
    }
    return q;
  }

  /** The finished part alone: the stock as the program leaves it, the machine hidden. */
  showFinished() {
    if (!this.stockView || !this.result || !this.result.machining) return;
    if (this.playing) this.toggle();
    const scene = this.app.scene(this.canvasId);
    if (scene.groups[0]) scene.groups[0].root.visible = false;
    this.stockView.showFinished();
    this.stockView.zoom();
  }

  /** Runs `program` on the selected machine and shows the result. */
  async run(program, name, extra = {}) {
    const m = this.app.machine;
    // A name for the run, so that the stop button can cancel it on the server.
    this.job = `run-${Date.now()}-${Math.floor(Math.random() * 1e6)}`;
    const stop = this.root.querySelector(".stop");
    stop.disabled = false;
    const busy = this.root.querySelector(".busy");
    const job = this.job;
    // While the server works: "checking…", or the run's place when it waits for a free slot.
    const watch = async () => {
      const jobs = await get("/api/jobs").catch(() => null);
      if (this.job !== job) return;
      const ahead = jobs ? jobs.queued.indexOf(job) : -1;
      busy.textContent = ahead >= 0 ? `queued: ${ahead + 1} of ${jobs.queued.length} waiting for a free slot` : "checking…";
      this.watchTimer = setTimeout(watch, 500);
    };
    busy.textContent = "checking…";
    this.watchTimer = setTimeout(watch, 300);
    document.body.classList.add("busy");
    let r;
    const machining = this.machiningRequest();
    if (machining) extra = { ...extra, machining };
    try {
      r = await post("/api/gcode/run", {
        machine: m.name,
        program,
        name,
        max_points: 20000,
        frames: 1500,
        job: this.job,
        ...extra,
      });
    } finally {
      stop.disabled = true;
      this.job = null;
      clearTimeout(this.watchTimer);
      busy.textContent = "";
      document.body.classList.remove("busy");
    }
    this.result = r;
    this.show(r, m);
    return r;
  }

  /** Draws machine `m` (GET /api/machines/NAME) at home: the 3-D area is never blank. */
  showMachine(m) {
    const scene = this.app.scene(this.canvasId);
    scene.frame(m.drawing);
    this.scale = scene.size;
    if (m.drawing.base_points.length)
      scene.draw(0, m.drawing, { scale: this.scale, diameter: m.machine.strut_diameter || 0, type: m.type, hybrid: m.machine.hybrid });
  }

  /** Forgets the last result: nothing of another program or machine stays on screen. */
  clear() {
    if (this.playing) this.toggle();
    this.result = null;
    const scene = this.app.scene(this.canvasId);
    scene.clear(0);
    scene.showPath([]);
    if (this.stockView) this.stockView.clear();
    this.root.querySelector(".mach-part").disabled = true;
    this.root.querySelector(".mach-zoom").disabled = true;
    for (const sel of [".summary", ".plots", ".violations"]) this.root.querySelector(sel).innerHTML = "";
    this.root.querySelector(".scrub").value = 0;
    this.root.querySelector(".clock").textContent = "0.00 s";
  }

  show(r, m) {
    const scene = this.app.scene(this.canvasId);
    scene.clear(0);
    if (r.frames.rows.length) scene.frame(r.frames.rows[0]);
    const toUnit = m.units === "inch" ? 1 / 25.4 : 1; // the path's positions are in mm
    scene.showPath(r.path.pose.map((p) => [p[0] * toUnit, p[1] * toUnit, p[2] * toUnit]));
    this.scale = scene.size;
    const checks = Object.entries(r.checks)
      .map(([name, c]) => ({ name, ...c }))
      .map((c) => `<span class="${!c.enabled ? "off" : c.violations ? "bad" : "ok"}" title="${c.off_reason || ""}">${c.name} ${!c.enabled ? "n/a" : c.violations ? c.violations + " violations" : "ok"}</span>`)
      .join(" ");
    this.root.querySelector(".summary").innerHTML =
      `<b class="${r.ok ? "ok" : "bad"}">${r.ok ? "every check passed" : "violations"}</b> ${r.points} points, cycle ${r.cycle_time_s.toFixed(2)} s<br>${checks}`;
    const list = this.root.querySelector(".violations");
    list.innerHTML = "";
    for (const g of groupViolations(r.violations).slice(0, 500)) {
      const li = document.createElement("li");
      const at = g.position.slice(0, 3).map((x) => Number(x).toFixed(2)).join(" ");
      li.textContent = `line ${g.line}: ${g.check} ${g.item} ${Number(g.value).toPrecision(5)} (limit ${Number(g.limit).toPrecision(5)} ${g.unit}, margin ${Number(g.margin).toPrecision(3)}) at X Y Z ${at}${g.count > 1 ? ` · ${g.count} points` : ""}`;
      li.dataset.line = g.line;
      li.addEventListener("click", () => this.jumpTo(g.line, g.position));
      list.appendChild(li);
    }
    this.showMachining(r, toUnit, list);
    this.plot(r, m);
    this.root.querySelector(".scrub").max = r.frames.t.at(-1) || 1;
    this.seek(0);
  }

  /** The stock of a run with the machining preview, its summary and its collisions. */
  showMachining(r, toUnit, list) {
    if (this.stockView) this.stockView.clear();
    const mach = r.machining;
    this.root.querySelector(".mach-part").disabled = !mach;
    this.root.querySelector(".mach-zoom").disabled = !mach;
    if (!mach) return;
    this.stockView = this.stockView || new StockView(this.app.scene(this.canvasId));
    this.stockView.show(mach, r.path, toUnit);
    const removed = (mach.initial_volume_mm3 - mach.final_volume_mm3) / 1000;
    const collisions = Object.values(mach.event_counts).reduce((a, b) => a + b, 0);
    const summary = document.createElement("div");
    summary.className = "machining-summary";
    summary.innerHTML = `<b class="${collisions ? "bad" : "ok"}">machining: ${collisions ? `${mach.events.length} collisions` : "no collision"}</b> · ${mach.stock.text}, ${mach.nx}×${mach.ny} cells of ${mach.cell.toPrecision(3)} mm · removed ${removed.toFixed(2)} cm³ in ${mach.seconds.toFixed(2)} s` + (mach.frames_complete ? "" : " · the animation stops early (too many changes): “finished part” shows the end");
    this.root.querySelector(".summary").appendChild(summary);
    for (const e of [...mach.events].reverse()) {
      const li = document.createElement("li");
      const what = { rapid: "rapid move through the stock", holder: "tool holder in the stock", table: "below the table", platform: "platform in the stock" }[e.kind] || e.kind;
      li.className = "collision";
      li.textContent = `line ${e.line}: ${what}, ${e.depth.toFixed(3)} mm deep at tip X Y Z ${e.tip.map((x) => x.toFixed(2)).join(" ")} (t ${e.t.toFixed(2)} s${e.count > 1 ? ` · ${e.count} positions` : ""})`;
      li.dataset.line = e.line;
      li.addEventListener("click", () => {
        if (this.onLine) this.onLine(e.line);
        this.seek(e.t);
      });
      list.insertBefore(li, list.firstChild);
    }
  }

  /**
   * Selects `line` (through onLine) and moves the animation to the moment on it nearest to
   * `position` (x y z a b c, mm and degrees: a violation's worst point), or its first moment.
   */
  jumpTo(line, position = null) {
    if (this.onLine) this.onLine(line);
    const p = this.result.path;
    let best = -1;
    let bestDistance = Infinity;
    for (let k = 0; k < p.line.length; ++k) {
      if (p.line[k] !== line) continue;
      if (!position) {
        best = k;
        break;
      }
      const d = p.pose[k].reduce((sum, x, i) => sum + (x - position[i]) ** 2, 0);
      if (d < bestDistance) [best, bestDistance] = [k, d];
    }
    if (best >= 0) this.seek(p.t[best]);
  }

  plot(r, m) {
    const box = this.root.querySelector(".plots");
    box.innerHTML = "";
    const t = r.path.t;
    const joints = r.path.joints;
    const width = Math.max(300, box.clientWidth || 500);
    const series = [{ label: "t s" }];
    const data = [t];
    joints.forEach((name, j) => {
      series.push({ label: name, stroke: `hsl(${(j * 57) % 360} 70% 45%)` });
      data.push(r.path.q.map((q) => q[j]));
    });
    const strokes = (m.machine.struts || []).map((s) => s.stroke).filter(Boolean);
    if (strokes.length && m.type === "hexapod") {
      const lo = Math.max(...strokes.map((s) => s[0])), hi = Math.min(...strokes.map((s) => s[1]));
      if (Number.isFinite(lo)) series.push({ label: "stroke min", stroke: "#d7263d", dash: [6, 4] }), data.push(t.map(() => lo));
      if (Number.isFinite(hi)) series.push({ label: "stroke max", stroke: "#d7263d", dash: [6, 4] }), data.push(t.map(() => hi));
    }
    this.cursorPlots = [new uPlot({ title: `joints (${m.units}, deg)`, width, height: 200, series, scales: { x: { time: false } } }, data, box)];
    // Joint speeds between path points, against the limit.
    const vs = [t.slice(1)];
    const vseries = [{ label: "t s" }];
    joints.forEach((name, j) => {
      vseries.push({ label: name, stroke: `hsl(${(j * 57) % 360} 70% 45%)` });
      vs.push(t.slice(1).map((_, k) => {
        const dt = t[k + 1] - t[k];
        return dt > 0 ? Math.abs(r.path.q[k + 1][j] - r.path.q[k][j]) / dt : null;
      }));
    });
    vseries.push({ label: "limit", stroke: "#d7263d", dash: [6, 4] });
    vs.push(vs[0].map(() => r.max_joint_velocity));
    this.cursorPlots.push(new uPlot({ title: `joint speed (${m.units}/s${m.type === "exechon" ? "; wrist deg/s" : ""})`, width, height: 160, series: vseries, scales: { x: { time: false } } }, vs, box));
    // The checks' margins at the frames (the server's checks of the drawn moments): the smallest
    // stroke margin, the leg-to-leg clearance and the condition margin; below zero is a violation.
    const rows = r.frames.rows;
    const least = (a) => (a && a.length ? Math.min(...a.filter((v) => v !== null)) : null);
    const ms = [r.frames.t, rows.map((w) => least(w.stroke_margin)), rows.map((w) => w.clearance), rows.map((w) => w.condition_margin), r.frames.t.map(() => 0)];
    this.cursorPlots.push(
      new uPlot(
        {
          title: `margins (${m.units}; condition: ratio)`,
          width,
          height: 160,
          series: [{ label: "t s" }, { label: "stroke", stroke: "#2563eb" }, { label: "clearance", stroke: "#7b2cbf" }, { label: "condition", stroke: "#059669", scale: "c" }, { label: "limit", stroke: "#d7263d", dash: [6, 4] }],
          scales: { x: { time: false } },
          axes: [{}, {}, { scale: "c", side: 1, grid: { show: false } }],
        },
        ms,
        box,
      ),
    );
  }

  /** Shows the machine at time `time` (s). */
  seek(time) {
    const r = this.result;
    if (!r || !r.frames.rows.length) return;
    this.time = time;
    const ft = r.frames.t;
    let k = 0;
    while (k + 1 < ft.length && ft[k + 1] <= time) ++k;
    const row = r.frames.rows[k];
    if (row.base_points.length)
      this.app.scene(this.canvasId).draw(0, row, { scale: this.scale, diameter: this.app.machine.machine.strut_diameter || 0, type: this.app.machine.type });
    const scene = this.app.scene(this.canvasId);
    if (scene.groups[0]) scene.groups[0].root.visible = true;
    if (this.stockView) this.stockView.at(time);
    this.root.querySelector(".scrub").value = time;
    this.root.querySelector(".clock").textContent = `${time.toFixed(2)} s  line ${r.path.line[r.frames.index[k]] ?? ""}`;
  }

  toggle() {
    this.playing = !this.playing;
    this.root.querySelector(".play").textContent = this.playing ? "❚❚ pause" : "▶ play";
    if (!this.playing || !this.result) return;
    let last = performance.now();
    const end = this.result.frames.t.at(-1) || 0;
    if (this.time >= end) this.time = 0;
    const step = (now) => {
      if (!this.playing) return;
      const speed = Number(this.root.querySelector(".speed").value);
      const t = Math.min(end, this.time + ((now - last) / 1000) * speed);
      last = now;
      this.seek(t);
      if (t >= end) return this.toggle();
      requestAnimationFrame(step);
    };
    requestAnimationFrame(step);
  }
}

export class ProgramView {
  constructor(root, app) {
    this.app = app;
    root.innerHTML = `
      <div class="editor-pane">
        <div class="toolbar">
          <button id="run">Run</button>
          <label>tolerance <input id="tolerance" type="number" step="any" placeholder="default"></label>
          <label>tool table <input id="tool-table" type="file" accept=".tbl"></label>
          <label title="a program, or a program and its tool table (.tbl) chosen together">open <input id="open-ngc" type="file" accept=".ngc,.nc,.txt,.tbl" multiple></label>
          <button id="save-ngc">save .ngc</button>
        </div>
        <div id="editor"></div>
        <div id="live-ahead"></div>
        <div id="program-error" class="error"></div>
      </div>
      <div class="canvas" id="program-canvas"></div>
      <div class="side wide" id="program-results"></div>`;
    this.editor = new EditorView({
      doc: EXAMPLE,
      extensions: [basicSetup, gcodeLanguage, lineMarks, liveMarks, EditorView.lineWrapping],
      parent: root.querySelector("#editor"),
    });
    this.sim = new Simulator(root.querySelector("#program-results"), app, "program-canvas", {
      onLine: (line) => this.selectLine(line),
    });
    this.toolTable = "";
    root.querySelector("#run").addEventListener("click", () => this.run());
    root.querySelector("#tool-table").addEventListener("change", async (e) => {
      this.toolTable = e.target.files[0] ? await e.target.files[0].text() : "";
    });
    root.querySelector("#open-ngc").addEventListener("change", async (e) => {
      const files = [...e.target.files];
      // A tool table chosen with the program is its tool table (LinuxCNC finds it in the INI).
      const tbl = files.find((f) => f.name.toLowerCase().endsWith(".tbl"));
      if (tbl) this.toolTable = await tbl.text();
      const file = files.find((f) => !f.name.toLowerCase().endsWith(".tbl"));
      if (!file) return;
      this.setProgram(await file.text());
      this.fileName = file.name;  // errors and saving name the file the user opened
      this.sim.clear();
    });
    root.querySelector("#save-ngc").addEventListener("click", () => this.app.download(this.fileName || "program.ngc", this.program()));
  }

  program() {
    return this.editor.state.doc.toString();
  }

  setProgram(text) {
    this.editor.dispatch({ changes: { from: 0, to: this.editor.state.doc.length, insert: text } });
  }

  selectLine(n) {
    const doc = this.editor.state.doc;
    if (n < 1 || n > doc.lines) return;
    const line = doc.line(n);
    this.editor.dispatch({ selection: EditorSelection.single(line.from, line.to), scrollIntoView: true });
    this.editor.focus();
  }

  markError(n) {
    const doc = this.editor.state.doc;
    const marks = n >= 1 && n <= doc.lines ? Decoration.set([badLine.range(doc.line(n).from)]) : Decoration.none;
    this.editor.dispatch({ effects: markLine.of(marks) });
  }

  /**
   * A record of the followed LinuxCNC: a newly loaded program is fetched, shown and checked on the
   * machine; its executing line is marked and the first violation ahead of it named.
   */
  async followLive(j) {
    const s = j.status;
    if (!j.connected || !s) return;
    if (s.file && s.file !== this.liveFile && !this.liveLoading) {
      this.liveLoading = true;
      try {
        const p = await get("/api/live/program");
        this.liveFile = s.file;
        this.liveName = s.file.split("/").pop();
        this.setProgram(p.text);
        this.liveLine = -1;
        this.liveResult = null;
        this.liveResult = await this.sim.run(p.text, this.liveName);
      } catch (e) {
        this.liveFile = s.file; // not again for the same file
        document.querySelector("#program-error").textContent = e.message;
        if (e.line) this.markError(e.line);
      } finally {
        this.liveLoading = false;
      }
    }
    if (s.file !== this.liveFile) return;
    const line = s.executing_line;
    if (line !== this.liveLine) {
      this.liveLine = line;
      const doc = this.editor.state.doc;
      const marks = line >= 1 && line <= doc.lines ? Decoration.set([liveLine.range(doc.line(line).from)]) : Decoration.none;
      this.editor.dispatch({ effects: markLive.of(marks), scrollIntoView: false });
      if (line >= 1 && line <= doc.lines) this.editor.dispatch({ effects: EditorView.scrollIntoView(doc.line(line).from, { y: "center" }) });
    }
    this.showAhead(line, j.state);
  }

  /** The first violation at or after the executing line (the program's own check). */
  showAhead(line, state) {
    const box = document.querySelector("#live-ahead");
    const r = this.liveResult;
    if (!r) return (box.textContent = "");
    const next = r.violations.find((v) => v.line >= Math.max(line, 1));
    box.dataset.line = next ? next.line : "";
    if (!next) {
      box.className = "ok";
      box.textContent = r.ok ? "LinuxCNC's program passes every check" : "no violation ahead of the executing line";
      return;
    }
    box.className = "bad";
    const where = state === "running" && line > 0 ? `${next.line - line} lines ahead of line ${line}` : "in the loaded program";
    box.textContent = `violation ahead, line ${next.line} (${where}): ${next.check} ${next.item} ${Number(next.value).toPrecision(5)}, limit ${Number(next.limit).toPrecision(5)} ${next.unit}`;
  }

  endLive() {
    this.liveFile = null;
    this.liveResult = null;
    this.editor.dispatch({ effects: markLive.of(Decoration.none) });
    document.querySelector("#live-ahead").textContent = "";
  }

  async run() {
    const err = document.querySelector("#program-error");
    err.textContent = "";
    this.markError(0);
    const tol = document.querySelector("#tolerance").value;
    try {
      const extra = {};
      if (tol) extra.tolerance = Number(tol);
      if (this.toolTable) extra.tool_table = this.toolTable;
      return await this.sim.run(this.program(), this.fileName || "program.ngc", extra);
    } catch (e) {
      this.sim.clear();
      err.textContent = e.message;
      if (e.line) {
        this.markError(e.line);
        this.selectLine(e.line);
      }
      return null;
    }
  }
}
