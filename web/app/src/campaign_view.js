// The Campaign view: a built-in campaign run on the server with live progress (server-sent
// events), each step's results as it finishes, then its report.
import { get, streamCampaign } from "./api.js";

export class CampaignView {
  constructor(root, app) {
    this.app = app;
    root.innerHTML = `
      <div class="side">
        <h3>Campaign</h3>
        <select id="campaign-name"></select>
        <button id="campaign-run">Run</button>
        <progress id="campaign-progress" max="1" value="0"></progress>
        <ol id="campaign-log"></ol>
      </div>
      <iframe id="campaign-report" title="campaign report"></iframe>`;
    root.querySelector("#campaign-run").addEventListener("click", () => this.run());
  }

  async load() {
    const list = await get("/api/campaigns");
    document.querySelector("#campaign-name").innerHTML = list
      .map((c) => `<option value="${c.name}" title="${c.description.replace(/"/g, "&quot;")}">${c.name} (${c.steps} steps)</option>`)
      .join("");
  }

  /** One finished step: its title and each row's before → after against the target. */
  showStep(log, step) {
    const li = document.createElement("li");
    li.className = "campaign-step";
    const fmt = (v) => (v === null || v === undefined ? "–" : Number(v).toPrecision(4));
    const esc = (t) => String(t).replace(/[&<>"]/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" })[c]);
    const rows = step.rows
      .map((r) => {
        const mark = r.target === null ? "" : r.pass ? "✓" : "✗";
        const target = r.target === null ? "" : ` (target ${fmt(r.target)})`;
        return `<tr class="${r.target === null ? "" : r.pass ? "ok" : "bad"}"><td>${mark}</td><td>${esc(r.quantity)}</td><td>${fmt(r.before)} → ${fmt(r.after)} ${esc(r.unit)}${target}</td></tr>`;
      })
      .join("");
    li.innerHTML = `<b></b><table>${rows}</table>`;
    li.querySelector("b").textContent = `${step.id}: ${step.title}`;
    log.appendChild(li);
  }

  async run() {
    const log = document.querySelector("#campaign-log");
    const bar = document.querySelector("#campaign-progress");
    log.innerHTML = "";
    bar.value = 0;
    this.finished = false;
    let report = null; // shown once the event stream has ended
    const line = (text, cls = "") => {
      const li = document.createElement("li");
      li.textContent = text;
      li.className = cls;
      log.appendChild(li);
    };
    try {
      await streamCampaign(document.querySelector("#campaign-name").value, (name, data) => {
        if (name === "progress") {
          if (data.count) bar.value = data.index / data.count;
          line(`${data.elapsed.toFixed(1)} s  ${data.message}`);
        } else if (name === "step") this.showStep(log, data);
        else if (name === "notice") line(data.message, "note");
        else if (name === "result") {
          bar.value = 1;
          line(data.all_pass ? "every target met" : "some targets missed", data.all_pass ? "ok" : "bad");
          report = data.report;
        } else if (name === "error") line(data.error, "bad");
      });
    } catch (e) {
      this.app.error(e);
    }
    if (report) document.querySelector("#campaign-report").src = report;
    this.finished = true; // the event stream has ended
  }
}
