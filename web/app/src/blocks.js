// The command icons of Lee et al. ("Development of a Parallel-Typed CNC Machine") as Blockly
// blocks, and the G-code they generate: moves (rapid, feed, arcs, platform orientation), modes,
// feed and spindle, dwell, loops and conditions (O-words), subroutines, and composite machining
// commands (sphere, circular pocket, drilling pattern, face mill, made by the library through the
// server). generate() returns the program and, for each of its lines, the block that wrote it.
import * as Blockly from "blockly/core";

const num = (name, value) => ({ type: "field_number", name, value });
const n = (b, name) => Number(b.getFieldValue(name));
const f = (v) => {
  const s = Number(v).toFixed(4).replace(/\.?0+$/, "");
  return s === "-0" ? "0" : s;
};

const MOVE = 210, MODE = 160, FLOW = 120, COMPOSITE = 20;

/** The block definitions (JSON), registered once. */
const definitions = [
  { type: "pkm_rapid", message0: "rapid to X %1 Y %2 Z %3", args0: [num("X", 0), num("Y", 0), num("Z", 200)], colour: MOVE },
  { type: "pkm_line", message0: "feed to X %1 Y %2 Z %3", args0: [num("X", 0), num("Y", 0), num("Z", 200)], colour: MOVE },
  {
    type: "pkm_arc",
    // END "FULL": a full circle about the centre offset, valid wherever the tool is (the palette's
    // default); "XY": to the end point X Y, which must lie on that circle (files saved before).
    message0: "arc %1 %2 X %3 Y %4 centre offset I %5 J %6",
    args0: [
      { type: "field_dropdown", name: "DIR", options: [["clockwise", "G2"], ["counter-clockwise", "G3"]] },
      { type: "field_dropdown", name: "END", options: [["to", "XY"], ["full circle, ignoring", "FULL"]] },
      num("X", 0),
      num("Y", 0),
      num("I", 10),
      num("J", 0),
    ],
    colour: MOVE,
  },
  { type: "pkm_orient", message0: "orient platform A %1 B %2 C %3 (deg)", args0: [num("A", 0), num("B", 0), num("C", 0)], colour: MOVE },
  {
    type: "pkm_mode",
    message0: "%1 coordinates",
    args0: [{ type: "field_dropdown", name: "MODE", options: [["absolute", "G90"], ["relative", "G91"]] }],
    colour: MODE,
  },
  { type: "pkm_feed", message0: "feed rate %1 per min", args0: [num("F", 600)], colour: MODE },
  {
    type: "pkm_spindle",
    message0: "spindle %1 at %2 rpm",
    args0: [{ type: "field_dropdown", name: "DIR", options: [["on (cw)", "M3"], ["on (ccw)", "M4"], ["off", "M5"]] }, num("S", 8000)],
    colour: MODE,
  },
  { type: "pkm_dwell", message0: "dwell %1 s", args0: [num("P", 0.5)], colour: MODE },
  {
    // Cutter radius compensation (G41.1/G42.1 with the diameter, G40): the tool centre runs one
    // radius beside the programmed contour (docs/gcode.md "Cutter radius compensation").
    type: "pkm_comp",
    message0: "cutter compensation %1 tool diameter %2",
    args0: [
      { type: "field_dropdown", name: "SIDE", options: [["tool left of path", "G41.1"], ["tool right of path", "G42.1"], ["off", "G40"]] },
      num("D", 6),
    ],
    colour: MODE,
  },
  { type: "pkm_set", message0: "set #<%1> = %2", args0: [{ type: "field_input", name: "VAR", text: "i" }, num("VALUE", 0)], colour: FLOW },
  { type: "pkm_add", message0: "add %2 to #<%1>", args0: [{ type: "field_input", name: "VAR", text: "i" }, num("VALUE", 1)], colour: FLOW },
  { type: "pkm_repeat", message0: "repeat %1 times", args0: [num("N", 3)], message1: "%1", args1: [{ type: "input_statement", name: "DO" }], colour: FLOW },
  {
    type: "pkm_while",
    message0: "while #<%1> %2 %3",
    args0: [{ type: "field_input", name: "VAR", text: "i" }, { type: "field_dropdown", name: "OP", options: [["<", "LT"], ["≤", "LE"], [">", "GT"], ["≥", "GE"], ["=", "EQ"], ["≠", "NE"]] }, num("VALUE", 3)],
    message1: "%1",
    args1: [{ type: "input_statement", name: "DO" }],
    colour: FLOW,
  },
  {
    type: "pkm_if",
    message0: "if #<%1> %2 %3",
    args0: [{ type: "field_input", name: "VAR", text: "i" }, { type: "field_dropdown", name: "OP", options: [["<", "LT"], ["≤", "LE"], [">", "GT"], ["≥", "GE"], ["=", "EQ"], ["≠", "NE"]] }, num("VALUE", 0)],
    message1: "%1",
    args1: [{ type: "input_statement", name: "DO" }],
    colour: FLOW,
  },
  { type: "pkm_sub", message0: "subroutine %1", args0: [{ type: "field_input", name: "NAME", text: "part" }], message1: "%1", args1: [{ type: "input_statement", name: "DO" }], colour: FLOW, previousStatement: null, nextStatement: null },
  { type: "pkm_call", message0: "call %1", args0: [{ type: "field_input", name: "NAME", text: "part" }], colour: FLOW },
  {
    // A call with arguments: the subroutine reads them as #1, #2, ...
    type: "pkm_call_args",
    message0: "call %1 with #1… = %2",
    args0: [{ type: "field_input", name: "NAME", text: "part" }, { type: "field_input", name: "ARGS", text: "10 5" }],
    colour: FLOW,
  },
  { type: "pkm_param", message0: "move by parameters: %1 to X #%2 Y #%3 Z #%4", args0: [{ type: "field_dropdown", name: "G", options: [["feed", "G1"], ["rapid", "G0"]] }, num("PX", 1), num("PY", 2), num("PZ", 3)], colour: MOVE },
  {
    type: "pkm_sphere",
    // Two rows each: the composite blocks stay narrow enough for a 1,366 px screen.
    message0: "sphere: radius %1 centre X %2 Y %3 Z %4",
    args0: [num("R", 20), num("X", 0), num("Y", 0), num("Z", 180)],
    message1: "ball tool radius %1 levels %2",
    args1: [num("TR", 3), num("LEVELS", 6)],
    colour: COMPOSITE,
  },
  {
    type: "pkm_pocket",
    message0: "circular pocket: centre X %1 Y %2 radius %3 top Z %4",
    args0: [num("X", 0), num("Y", 0), num("R", 15), num("Z", 200)],
    message1: "depth %1 step-over %2 step-down %3",
    args1: [num("D", 4), num("S", 4), num("DZ", 2)],
    colour: COMPOSITE,
  },
  {
    type: "pkm_drill",
    message0: "drilling: %1 holes on a circle X %2 Y %3 radius %4",
    args0: [num("N", 6), num("X", 0), num("Y", 0), num("R", 30)],
    message1: "top Z %1 depth %2",
    args1: [num("Z", 200), num("D", 8)],
    colour: COMPOSITE,
  },
  {
    type: "pkm_face",
    message0: "face mill: X %1 to %2 Y %3 to %4",
    args0: [num("X0", -30), num("X1", 30), num("Y0", -30), num("Y1", 30)],
    message1: "at Z %1 step %2",
    args1: [num("Z", 195), num("S", 10)],
    colour: COMPOSITE,
  },
];

let registered = false;
export function registerBlocks() {
  if (registered) return;
  registered = true;
  Blockly.common.defineBlocksWithJsonArray(
    definitions.map((d) => ({ previousStatement: null, nextStatement: null, ...d })),
  );
}

export const toolbox = {
  kind: "categoryToolbox",
  contents: [
    { kind: "category", name: "Moves", colour: MOVE, contents: ["pkm_rapid", "pkm_line", "pkm_arc", "pkm_orient", "pkm_param"].map((type) => (type === "pkm_arc" ? { kind: "block", type, fields: { END: "FULL" } } : { kind: "block", type })) },
    { kind: "category", name: "Settings", colour: MODE, contents: ["pkm_mode", "pkm_feed", "pkm_spindle", "pkm_dwell", "pkm_comp"].map((type) => ({ kind: "block", type })) },
    { kind: "category", name: "Flow", colour: FLOW, contents: ["pkm_set", "pkm_add", "pkm_repeat", "pkm_while", "pkm_if", "pkm_sub", "pkm_call", "pkm_call_args"].map((type) => ({ kind: "block", type })) },
    { kind: "category", name: "Machining", colour: COMPOSITE, contents: ["pkm_sphere", "pkm_pocket", "pkm_drill", "pkm_face"].map((type) => ({ kind: "block", type })) },
  ],
};

/**
 * The composite blocks as the library's shapes (cnc/shapes.hpp, POST /api/gcode/shape): the
 * block's fields as the shape's parameters. The G-code is the server's, one definition for the
 * page, `pkm gcode make` and Python.
 */
const composites = {
  pkm_sphere: (b) => ({ shape: "sphere", values: { radius: n(b, "R"), x: n(b, "X"), y: n(b, "Y"), z: n(b, "Z"), tool_radius: n(b, "TR"), levels: n(b, "LEVELS") } }),
  pkm_pocket: (b) => ({ shape: "pocket", values: { x: n(b, "X"), y: n(b, "Y"), radius: n(b, "R"), top: n(b, "Z"), depth: n(b, "D"), stepover: n(b, "S"), stepdown: n(b, "DZ") } }),
  pkm_drill: (b) => ({ shape: "drill", values: { holes: n(b, "N"), x: n(b, "X"), y: n(b, "Y"), radius: n(b, "R"), top: n(b, "Z"), depth: n(b, "D") } }),
  pkm_face: (b) => ({ shape: "face", values: { x0: n(b, "X0"), x1: n(b, "X1"), y0: n(b, "Y0"), y1: n(b, "Y1"), z: n(b, "Z"), step: n(b, "S") } }),
};

/** The cache key of a shape request. */
export const shapeKey = (spec) => JSON.stringify(spec);

/** The words of a simple block, or null. */
function simple(b) {
  switch (b.type) {
    case "pkm_rapid":
      return `G0 X${f(n(b, "X"))} Y${f(n(b, "Y"))} Z${f(n(b, "Z"))}`;
    case "pkm_line":
      return `G1 X${f(n(b, "X"))} Y${f(n(b, "Y"))} Z${f(n(b, "Z"))}`;
    case "pkm_arc":
      if (b.getFieldValue("END") === "FULL") return `${b.getFieldValue("DIR")} I${f(n(b, "I"))} J${f(n(b, "J"))}`;
      return `${b.getFieldValue("DIR")} X${f(n(b, "X"))} Y${f(n(b, "Y"))} I${f(n(b, "I"))} J${f(n(b, "J"))}`;
    case "pkm_orient":
      return `G1 A${f(n(b, "A"))} B${f(n(b, "B"))} C${f(n(b, "C"))}`;
    case "pkm_mode":
      return b.getFieldValue("MODE");
    case "pkm_feed":
      return `F${f(n(b, "F"))}`;
    case "pkm_spindle":
      return b.getFieldValue("DIR") === "M5" ? "M5" : `${b.getFieldValue("DIR")} S${f(n(b, "S"))}`;
    case "pkm_dwell":
      return `G4 P${f(n(b, "P"))}`;
    case "pkm_set":
      return `#<${name(b, "VAR")}> = ${f(n(b, "VALUE"))}`;
    case "pkm_add":
      return `#<${name(b, "VAR")}> = [#<${name(b, "VAR")}> + ${f(n(b, "VALUE"))}]`;
    case "pkm_call":
      return `o<${name(b, "NAME")}> call`;
    case "pkm_call_args":
      return `o<${name(b, "NAME")}> call ${args(b)}`;
    case "pkm_comp":
      return b.getFieldValue("SIDE") === "G40" ? "G40" : `${b.getFieldValue("SIDE")} D${f(n(b, "D"))}`;
    case "pkm_param": {
      const p = (k) => Math.max(1, Math.min(30, Math.round(n(b, k))));
      return `${b.getFieldValue("G")} X#${p("PX")} Y#${p("PY")} Z#${p("PZ")}`;
    }
    default:
      return null;
  }
}

/** The argument field of a call block as O-word call arguments: numbers only ([10] [5]). */
function args(b) {
  return String(b.getFieldValue("ARGS"))
    .split(/[\s,;]+/)
    .filter((t) => t !== "" && Number.isFinite(Number(t)))
    .slice(0, 30)
    .map((t) => `[${f(Number(t))}]`)
    .join(" ");
}

/** A name field as an O-word or parameter name (letters, digits, _). */
function name(b, field) {
  return String(b.getFieldValue(field)).replace(/[^A-Za-z0-9_]/g, "_").toLowerCase() || "x";
}

/**
 * The program of workspace `ws`: subroutines first, then every other top stack in order (top to
 * bottom), between a preamble and M2. `shapes` maps shapeKey(spec) to the server's lines (or an
 * Error). Returns { text, blocks, missing, errors }: blocks[i] is the id of the block that wrote
 * line i + 1 (null for the preamble and the end); `missing` the shape requests not in `shapes`
 * (their blocks write a comment meanwhile), `errors` [block id, message] of refused ones.
 */
export function generate(ws, shapes = new Map()) {
  const missing = [];
  const errors = [];
  const lines = [];
  const blocks = [];
  const emit = (text, id) => {
    lines.push(text);
    blocks.push(id);
  };
  let label = 100;
  const walk = (b) => {
    for (; b; b = b.getNextBlock()) {
      if (b.isEnabled && !b.isEnabled()) continue;
      const s = simple(b);
      if (s !== null) emit(s, b.id);
      else if (composites[b.type]) {
        const spec = composites[b.type](b);
        const lines = shapes.get(shapeKey(spec));
        if (lines instanceof Error) {
          errors.push([b.id, lines.message]);
          emit(`(${spec.shape}: ${lines.message.replace(/[()]/g, "")})`, b.id);
        } else if (lines) for (const l of lines) emit(l, b.id);
        else {
          missing.push(spec);
          emit(`(${spec.shape}: being made)`, b.id);
        }
      }
      else if (b.type === "pkm_repeat" || b.type === "pkm_while" || b.type === "pkm_if") {
        const o = `o${label++}`;
        const [open, close] =
          b.type === "pkm_repeat"
            ? [`${o} repeat [${f(Math.max(0, Math.round(n(b, "N"))))}]`, `${o} endrepeat`]
            : b.type === "pkm_while"
              ? [`${o} while [#<${name(b, "VAR")}> ${b.getFieldValue("OP")} ${f(n(b, "VALUE"))}]`, `${o} endwhile`]
              : [`${o} if [#<${name(b, "VAR")}> ${b.getFieldValue("OP")} ${f(n(b, "VALUE"))}]`, `${o} endif`];
        emit(open, b.id);
        walk(b.getInputTargetBlock("DO"));
        emit(close, b.id);
      }
    }
  };
  const tops = ws.getTopBlocks(true);
  for (const b of tops.filter((t) => t.type === "pkm_sub")) {
    emit(`o<${name(b, "NAME")}> sub`, b.id);
    walk(b.getInputTargetBlock("DO"));
    emit(`o<${name(b, "NAME")}> endsub`, b.id);
  }
  emit("G21 G90 G17 F600 (pkm blocks)", null);
  for (const b of tops.filter((t) => t.type !== "pkm_sub")) walk(b);
  emit("M2", null);
  return { text: lines.join("\n") + "\n", blocks, missing, errors };
}
