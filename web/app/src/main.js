// The pkm serve web application (docs/web.md): one page, four views (Machine, Program, Blocks,
// Campaign), on the JSON API only. window.pkmApp is the page's state, for the browser tests.
import "./style.css";
import { get, post } from "./api.js";
import { MachineScene } from "./scene.js";
import { MachineView } from "./machine_view.js";
import { ProgramView } from "./program_view.js";
import { BlocksView } from "./blocks_view.js";
import { CampaignView } from "./campaign_view.js";
import { LiveFollower } from "./live.js";
import { LiveCalibration } from "./live_calibration.js";

const $ = (s) => document.querySelector(s);

class App {
  constructor() {
    this.scenes = {};
    this.machine = null;
    this.views = {
      machine: new MachineView($("#view-machine"), this),
      program: new ProgramView($("#view-program"), this),
      blocks: new BlocksView($("#view-blocks"), this),
      campaign: new CampaignView($("#view-campaign"), this),
    };
    for (const b of document.querySelectorAll("#views button")) b.addEventListener("click", () => this.showView(b.dataset.view));
    $("#machine").addEventListener("change", () => this.selectMachine($("#machine").value));
    $("#compare").addEventListener("change", () => this.selectMachine($("#machine").value));
    $("#upload").addEventListener("change", (e) => this.upload([...e.target.files]));
    $("#message-close").addEventListener("click", () => this.clearMessage());
    this.follower = new LiveFollower(this);
    this.calibration = new LiveCalibration($("#livecal-panel"), this);
  }

  /** One record of the followed LinuxCNC (GET /api/live): its machine is selected once known. */
  async live(j) {
    if (j.machine && this.machine?.name !== "linuxcnc") {
      if (this.switching) return;
      this.switching = true;
      try {
        await this.loadMachines("linuxcnc");
      } finally {
        this.switching = false;
      }
    }
    if (this.machine?.name !== "linuxcnc") return;
    this.views.machine.showLive(j);
    await this.views.program.followLive(j);
  }

  /** Following ended: the views go back to their own poses and programs. */
  liveStopped() {
    this.views.machine.endLive();
    this.views.program.endLive();
  }

  /** The 3-D scene in the element with id `id` (made on first use). */
  scene(id) {
    if (!this.scenes[id]) this.scenes[id] = new MachineScene(document.getElementById(id));
    return this.scenes[id];
  }

  showView(name) {
    for (const o of document.querySelectorAll("#views button")) o.classList.toggle("active", o.dataset.view === name);
    for (const v of document.querySelectorAll(".view")) v.classList.toggle("active", v.id === "view-" + name);
    for (const s of Object.values(this.scenes)) s.resize();
    if (name === "blocks") this.views.blocks.resize();
    this.view = name;
  }

  /** Shows an error (red) or a notice (amber) under the header, where it is seen at any width. */
  error(e) {
    this.say(e.message || String(e), "error");
    console.warn(e);
  }

  say(text, kind = "notice") {
    $("#message-text").textContent = text;
    $("#message").className = kind;
    $("#message").hidden = !text;
  }

  clearMessage() {
    this.say("");
  }

  download(name, text) {
    const a = document.createElement("a");
    a.href = URL.createObjectURL(new Blob([text], { type: "text/plain" }));
    a.download = name;
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }

  async loadMachines(select) {
    const list = await get("/api/machines");
    const options = list.map((m) => `<option value="${m.name}">${m.name} (${m.type}, ${m.units})</option>`).join("");
    $("#machine").innerHTML = options;
    $("#compare").innerHTML = `<option value="">(none)</option>` + options;
    if (select) $("#machine").value = select;
    await this.selectMachine($("#machine").value);
  }

  async selectMachine(name) {
    this.clearMessage();
    try {
      this.machine = await get(`/api/machines/${encodeURIComponent(name)}`);
      const other = $("#compare").value;
      const compare = other && other !== name ? await get(`/api/machines/${encodeURIComponent(other)}`) : null;
      if (compare && compare.type !== this.machine.type) throw new Error(`${other} is not a ${this.machine.type}`);
      this.views.machine.show(this.machine, compare);
      // Results of the previous machine are not this machine's.
      for (const v of [this.views.program, this.views.blocks]) {
        v.sim?.clear();
        v.sim?.showMachine(this.machine);
      }
      document.body.dataset.machine = name;
    } catch (e) {
      this.error(e);
    }
  }

  /** Uploads a machine file: a .json, or a LinuxCNC .hal with its .ini chosen together. */
  async upload(files) {
    if (!files.length) return;
    const machine = files.find((f) => !f.name.toLowerCase().endsWith(".ini"));
    const ini = files.find((f) => f.name.toLowerCase().endsWith(".ini"));
    try {
      if (!machine) throw new Error(`${ini.name}: choose the machine's .hal (or .json) together with its .ini`);
      const body = { filename: machine.name, text: await machine.text() };
      if (ini) body.ini = await ini.text();
      const r = await post("/api/machines", body);
      await this.loadMachines(r.name);
      if (r.notices.length) this.say(r.notices.join("; "));
    } catch (e) {
      this.error(e);
    } finally {
      $("#upload").value = "";  // choosing the same files again uploads them again
    }
  }
}

const app = new App();
window.pkmApp = app;
app.ready = Promise.all([app.loadMachines(), app.views.campaign.load()]).then(() => app.follower.init());
