// Following a running LinuxCNC (docs/linuxcnc.md, "The live machine"): while following, GET
// /api/live 20 times a second; the Machine view draws the machine as LinuxCNC commands it and the
// Program view shows LinuxCNC's program, its executing line and the violations ahead of it.
// Following only reads; the one routine that moves the machine is live_calibration.js's.
import { get, post } from "./api.js";

const PERIOD_MS = 50;

export class LiveFollower {
  constructor(app) {
    this.app = app;
    this.button = document.querySelector("#live-connect");
    this.label = document.querySelector("#live-status");
    this.following = false;
    this.last = null;
    this.button.addEventListener("click", () => (this.following ? this.stop() : this.start()));
  }

  /** Follows from the start when the server does (`pkm serve --linuxcnc`). */
  async init() {
    const j = await get("/api/live");
    this.show(j);
    if (j.following) this.begin();
  }

  async start() {
    try {
      this.show(await post("/api/live/connect", {}));
      this.begin();
    } catch (e) {
      this.app.error(e);
    }
  }

  async stop() {
    this.following = false;
    clearTimeout(this.timer);
    this.button.textContent = "Connect LinuxCNC";
    await post("/api/live/disconnect", {}).catch(() => {});
    this.show({ following: false, state: "not following", reason: "" });
    this.app.liveStopped();
  }

  begin() {
    if (this.following) return;
    this.following = true;
    this.button.textContent = "Disconnect";
    this.tick();
  }

  async tick() {
    if (!this.following) return;
    const started = performance.now();
    try {
      const j = await get("/api/live");
      this.last = j;
      this.show(j);
      await this.app.live(j);
    } catch (e) {
      this.show({ following: true, connected: false, state: "disconnected", reason: e.message });
    }
    this.timer = setTimeout(() => this.tick(), Math.max(0, PERIOD_MS - (performance.now() - started)));
  }

  /** The header's line: LinuxCNC's state, program and line; red when it cannot move. */
  show(j) {
    const s = j.status;
    let text = `LinuxCNC: ${j.state}`;
    if (j.connected && s && s.file) text += ` · ${s.file.split("/").pop()}${s.executing_line ? ` line ${s.executing_line}` : ""}`;
    if (!j.connected && j.reason) text += ` (${j.reason})`;
    if (j.machine_error) text += ` · machine: ${j.machine_error}`;
    this.label.textContent = j.following ? text : "";
    const good = j.connected && ["idle", "running", "paused"].includes(j.state);
    this.label.className = good ? "live-ok" : j.following ? "live-bad" : "";
    document.body.dataset.live = j.state || "";
    if (document.body.classList.contains("following") !== Boolean(j.following)) {
      document.body.classList.toggle("following", Boolean(j.following));
      for (const scene of Object.values(this.app.scenes)) scene.resize();
    }
  }
}
