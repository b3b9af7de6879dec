// The Blocks view (the graphic programming of Lee et al., "Development of a Parallel-Typed CNC
// Machine"): a Blockly workspace of command icons connected into a program, its G-code beside it,
// Run in the simulator, violations marked on the blocks that wrote them; programs save to and load
// from a file (Blockly JSON) and export as .ngc.
import * as Blockly from "blockly/core";
import * as En from "blockly/msg/en";
import { registerBlocks, toolbox, generate, shapeKey } from "./blocks.js";
import { post } from "./api.js";
import { Simulator } from "./program_view.js";

Blockly.setLocale(En);

/** A first program: approach, a sphere, retract. */
const STARTER = {
  blocks: {
    languageVersion: 0,
    blocks: [
      {
        type: "pkm_feed", x: 20, y: 20, fields: { F: 600 },
        next: { block: { type: "pkm_rapid", fields: { X: 0, Y: 0, Z: 230 },
          next: { block: { type: "pkm_sphere", fields: { R: 20, X: 0, Y: 0, Z: 180, TR: 3, LEVELS: 5 },
            next: { block: { type: "pkm_rapid", fields: { X: 0, Y: 0, Z: 230 } } } } } } },
      },
    ],
  },
};

export class BlocksView {
  constructor(root, app) {
    this.app = app;
    this.shapes = new Map(); // shapeKey(spec) -> lines, or the Error the server answered
    this.shapeWarned = new Set(); // blocks whose warning is a refused shape
    registerBlocks();
    root.innerHTML = `
      <div class="blocks-pane">
        <div class="toolbar">
          <button id="blocks-run">Run</button>
          <button id="blocks-save">save program</button>
          <label>load <input id="blocks-load" type="file" accept=".json"></label>
          <button id="blocks-export">export .ngc</button>
        </div>
        <div id="blockly"></div>
      </div>
      <div class="code-pane"><pre id="blocks-code"></pre><div id="blocks-error" class="error"></div></div>
      <div class="canvas" id="blocks-canvas"></div>
      <div class="side wide" id="blocks-results"></div>`;
    this.workspace = Blockly.inject(root.querySelector("#blockly"), {
      toolbox,
      media: "/media/",
      sounds: false,
      trashcan: false,
      zoom: { controls: false, wheel: true, startScale: 0.8 },
      move: { scrollbars: true, drag: true, wheel: false },
      renderer: "thrasos",
    });
    Blockly.serialization.workspaces.load(STARTER, this.workspace);
    this.workspace.addChangeListener((e) => {
      if (!e.isUiEvent) this.refresh();
    });
    this.sim = new Simulator(root.querySelector("#blocks-results"), app, "blocks-canvas", {
      onLine: (line) => this.selectLine(line),
    });
    root.querySelector("#blocks-run").addEventListener("click", () => this.run());
    root.querySelector("#blocks-export").addEventListener("click", async () => app.download("blocks.ngc", (await this.ready()).text));
    root.querySelector("#blocks-save").addEventListener("click", () =>
      app.download("program.blocks.json", JSON.stringify(Blockly.serialization.workspaces.save(this.workspace), null, 1)),
    );
    root.querySelector("#blocks-load").addEventListener("change", async (e) => {
      if (!e.target.files[0]) return;
      try {
        this.load(JSON.parse(await e.target.files[0].text()));
      } catch (err) {
        app.error(err);
      }
    });
    this.refresh();
  }

  /** Asks the server for the composite blocks' G-code not made yet (all at once). */
  async fetchShapes(missing) {
    await Promise.all(
      missing.map(async (spec) => {
        const key = shapeKey(spec);
        if (this.shapes.has(key)) return;
        try {
          this.shapes.set(key, (await post("/api/gcode/shape", spec)).lines);
        } catch (e) {
          this.shapes.set(key, e instanceof Error ? e : new Error(String(e)));
        }
      }),
    );
  }

  /** The program with every composite block's G-code made (the server asked as needed). */
  async ready() {
    for (let g = this.code(); ; g = this.code()) {
      if (!g.missing.length) return g;
      await this.fetchShapes(g.missing);
    }
  }

  /** Replaces the workspace with a saved program (Blockly JSON). */
  load(state) {
    this.workspace.clear();
    Blockly.serialization.workspaces.load(state, this.workspace);
    this.refresh();
  }

  /** The program as far as it is known now (composite blocks not made yet write a comment). */
  code() {
    return generate(this.workspace, this.shapes || new Map());
  }

  refresh() {
    const g = this.code();
    document.querySelector("#blocks-code").textContent = g.text
      .split("\n")
      .map((l, i) => (l ? `${String(i + 1).padStart(3)}  ${l}` : ""))
      .join("\n");
    // A refused shape's message on its block, until its fields are fixed.
    const refused = new Map(g.errors);
    for (const id of this.shapeWarned) if (!refused.has(id)) this.workspace.getBlockById(id)?.setWarningText(null);
    for (const [id, message] of refused) this.workspace.getBlockById(id)?.setWarningText(message);
    this.shapeWarned = new Set(refused.keys());
    if (g.missing.length) this.fetchShapes(g.missing).then(() => this.refresh());
  }

  /** Selects the block that wrote program line `line`. */
  selectLine(line) {
    const id = this.generated?.blocks[line - 1];
    const block = id && this.workspace.getBlockById(id);
    if (block) block.select();
  }

  resize() {
    Blockly.svgResize(this.workspace);
  }

  async run() {
    const err = document.querySelector("#blocks-error");
    err.textContent = "";
    for (const b of this.workspace.getAllBlocks(false)) b.setWarningText(null);
    this.marked = new Map(); // block id -> the warning set on it
    this.generated = await this.ready();
    if (this.generated.errors.length) {
      const [id, message] = this.generated.errors[0];
      this.workspace.getBlockById(id)?.setWarningText(message);
      err.textContent = message;
      return null;
    }
    try {
      const r = await this.sim.run(this.generated.text, "blocks.ngc");
      const marked = new Map();
      for (const v of r.violations) {
        const id = this.generated.blocks[v.line - 1];
        if (id && !marked.has(id)) marked.set(id, `${v.check} violated (${v.item}) at line ${v.line}`);
      }
      for (const [id, text] of marked) this.workspace.getBlockById(id)?.setWarningText(text);
      this.marked = marked;
      return r;
    } catch (e) {
      err.textContent = e.message;
      const id = e.line && this.generated.blocks[e.line - 1];
      if (id) this.workspace.getBlockById(id)?.setWarningText(e.message);
      return null;
    }
  }
}
