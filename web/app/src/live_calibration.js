// The automated calibration by constrained motion on the followed LinuxCNC (docs/linuxcnc.md,
// "Automated calibration by constrained motion"; docs/web.md, "The automated calibration"): the
// Machine view's panel. Nothing moves until the user confirms in a dialog that says what will
// happen; while the routine runs its event stream stays open (closing the page stops the
// machine), Stop cancels it, and after the fit the page asks before anything is installed.
import { post, streamEvents } from "./api.js";

const fmt = (v, d = 4) => (v === null || v === undefined ? "-" : Number(v).toFixed(d));

export class LiveCalibration {
  constructor(root, app) {
    this.app = app;
    root.innerHTML = `
      <details id="livecal">
        <summary>Calibrate by constrained motion</summary>
        <p class="note">Lee et al.'s calibration: pkm moves the platform through planned stations
        and, at each, until the three gauges on the table read zero; then fits the geometry.</p>
        <label>gauge pins <input id="livecal-gauges" size="30" value="pkmtruth.gauge-0,pkmtruth.gauge-1,pkmtruth.gauge-2"></label>
        <label>laser pin (x) <input id="livecal-laser" size="18" value="pkmtruth.laser-x"></label>
        <label>stations <input id="livecal-stations" type="number" min="14" max="400" value="36"></label>
        <label>held out <input id="livecal-holdout" type="number" min="0" max="100" value="4"></label>
        <label>settle s <input id="livecal-settle" type="number" min="0" step="0.01" value="0.1"></label>
        <label>tolerance mm <input id="livecal-tolerance" type="number" min="0" step="0.001" value="0.003"></label>
        <div class="livecal-buttons">
          <button id="livecal-start">Start…</button>
          <button id="livecal-stop" class="danger" disabled>Stop the machine</button>
        </div>
        <progress id="livecal-progress" max="1" value="0"></progress>
        <div id="livecal-stage"></div>
        <ol id="livecal-log"></ol>
        <pre id="livecal-report"></pre>
      </details>
      <dialog id="livecal-confirm">
        <h3>Move the machine?</h3>
        <p>pkm will send LinuxCNC MDI moves (G53 G0) through <b id="livecal-count"></b> stations
        around the home pose, each approached from below, and servo at each until the gauges read
        zero. Check that the gauges and the laser are set up and that the work area is clear.</p>
        <p>Keep this page open: closing it, losing the connection or pressing Stop aborts the
        motion at once. Nothing is installed without asking you again.</p>
        <button id="livecal-go" class="danger">Move the machine</button>
        <button id="livecal-no">Cancel</button>
      </dialog>
      <dialog id="livecal-install">
        <h3>Install the calibration?</h3>
        <div id="livecal-figures"></div>
        <p>Install writes the calibrated geometry into the configuration (with a backup), applies
        it to the running LinuxCNC (machine off and on; nothing moves) and re-measures the x
        move.</p>
        <button id="livecal-yes" class="danger">Install and re-measure</button>
        <button id="livecal-keep">Keep the configuration</button>
      </dialog>`;
    this.$ = (sel) => root.querySelector(sel);
    this.$("#livecal-start").addEventListener("click", () => this.ask());
    this.$("#livecal-no").addEventListener("click", () => this.$("#livecal-confirm").close());
    this.$("#livecal-go").addEventListener("click", () => {
      this.$("#livecal-confirm").close();
      this.run();
    });
    this.$("#livecal-stop").addEventListener("click", () => this.stop());
    this.$("#livecal-yes").addEventListener("click", () => this.answer(true));
    this.$("#livecal-keep").addEventListener("click", () => this.answer(false));
    this.running = false;
  }

  /** The request the server takes (POST /api/live/calibration), "confirm" aside. */
  request() {
    const n = (id) => Number(this.$(id).value);
    const body = {
      gauges: this.$("#livecal-gauges").value.split(",").map((p) => p.trim()),
      stations: n("#livecal-stations"),
      holdout_stations: n("#livecal-holdout"),
      settle: n("#livecal-settle"),
      tolerance: n("#livecal-tolerance"),
    };
    const laser = this.$("#livecal-laser").value.trim();
    if (laser) body.laser = laser;
    return body;
  }

  ask() {
    const r = this.request();
    this.$("#livecal-count").textContent = `${r.stations} + ${r.holdout_stations}`;
    this.$("#livecal-confirm").showModal();
  }

  line(text, cls = "") {
    const li = document.createElement("li");
    li.textContent = text;
    li.className = cls;
    const log = this.$("#livecal-log");
    log.appendChild(li);
    log.scrollTop = log.scrollHeight;
  }

  async run() {
    this.$("#livecal-log").innerHTML = "";
    this.$("#livecal-report").textContent = "";
    this.$("#livecal-progress").value = 0;
    this.setRunning(true);
    this.$("#livecal-stage").scrollIntoView({ block: "nearest" });
    this.outcome = null;
    try {
      await streamEvents("/api/live/calibration", { ...this.request(), confirm: true }, (name, data) =>
        this.onEvent(name, data),
      );
      if (!this.outcome) this.line("the server ended the routine without a result", "bad");
    } catch (e) {
      this.line(e.message, "bad");
      this.app.error(e);
    }
    this.$("#livecal-install").close();
    this.setRunning(false);
  }

  onEvent(name, d) {
    const stage = this.$("#livecal-stage");
    if (name === "started") this.line(`started on ${d.ini}`);
    else if (name === "progress") {
      if (d.count) this.$("#livecal-progress").value = d.index / d.count;
      stage.textContent = `${d.stage}: ${d.message}`;
      this.line(`${d.elapsed.toFixed(1)} s  ${d.stage} ${d.count ? `${d.index}/${d.count} ` : ""}${d.message}`);
    } else if (name === "confirm") {
      stage.textContent = "waiting for your answer";
      this.$("#livecal-figures").innerHTML = this.figures(d);
      this.$("#livecal-install").showModal();
    } else if (name === "result") {
      this.outcome = "result";
      this.$("#livecal-progress").value = 1;
      stage.textContent = d.installed ? "calibrated, installed and re-measured" : "calibrated (not installed)";
      this.line(stage.textContent, "ok");
      this.$("#livecal-report").textContent = d.report;
    } else if (name === "cancelled") {
      this.outcome = "cancelled";
      stage.textContent = "stopped: the machine's motion was aborted";
      this.line(`stopped (${d.message})`, "bad");
    } else if (name === "error") {
      this.outcome = "error";
      stage.textContent = "failed";
      this.line(d.error, "bad");
    }
  }

  figures(d) {
    const laser = d.laser_error_before === null ? "" : `<div>x move error before: <b>${fmt(d.laser_error_before)} mm</b></div>`;
    return `<div>${d.stations} stations fitted, ${d.held_out} held out; ${d.identifiable} of 42 parameter directions identifiable</div>
      <div>held-out gauge residuals RMS: <b>${fmt(d.holdout_rms_before)} mm</b> with the configuration's machine,
      <b>${fmt(d.holdout_rms_after)} mm</b> calibrated</div>${laser}`;
  }

  /**
   * Sends the answer; one that gets no reply within 5 s is sent again (at most 4 times: a
   * connection the browser reused as the server closed it must not leave the routine waiting).
   * A 409 "not asking now" means an earlier attempt arrived.
   */
  async answer(install) {
    this.$("#livecal-install").close();
    for (let attempt = 1; ; ++attempt) {
      const abort = new AbortController();
      const timer = setTimeout(() => abort.abort(), 5000);
      try {
        await post("/api/live/calibration/confirm", { install }, abort.signal);
        break;
      } catch (e) {
        if (e.status === 409) break;
        if (attempt >= 4) return this.app.error(e);
        this.line(`the answer got no reply (${e.message}): sent again`, "bad");
      } finally {
        clearTimeout(timer);
      }
    }
    this.line(install ? "install: yes" : "install: no (the configuration is kept)");
  }

  async stop() {
    try {
      await post("/api/live/calibration/cancel", {});
    } catch (e) {
      this.app.error(e);
    }
  }

  setRunning(on) {
    this.running = on;
    this.$("#livecal-start").disabled = on;
    this.$("#livecal-stop").disabled = !on;
    for (const input of this.$("#livecal").querySelectorAll("input")) input.disabled = on;
    document.body.classList.toggle("calibrating", on);
  }
}
