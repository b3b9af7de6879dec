// Browser test of the pkm serve web application (docs/web.md): starts `pkm serve --port 0`, opens
// the page in headless Chromium (Debian's /usr/bin/chromium driven by playwright-core) and checks
// each view: no console or page error, no request leaving 127.0.0.1, a 3-D canvas with drawn
// pixels; example sphere.ngc gives the same check results as `pkm gcode run --report`; a stroke
// violation is listed and clicking it selects its line; a Blockly program built here generates
// the expected G-code and marks the block whose move violates a check; the Exechon is drawn and
// runs its example; the default campaign streams to its report. Screenshots go to OUT_DIR.
//
//   node app_browser_test.mjs PKM_BINARY SOURCE_DIR OUT_DIR
//
// Exit codes: 0 pass, 1 fail, 77 skipped (no chromium or no web/app/node_modules).
import { spawnSync } from "node:child_process";
import { mkdirSync, mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { checker, chromiumOrSkip, drawnPixels, launch, startServer, watchedPage } from "./harness.mjs";

const MIN_DRAWN_PIXELS = 2000; // a drawn machine covers far more of the canvas than this

const [pkmBinary, sourceDir, outDir] = process.argv.slice(2);
if (!pkmBinary || !sourceDir || !outDir) {
  console.error("usage: app_browser_test.mjs PKM_BINARY SOURCE_DIR OUT_DIR");
  process.exit(1);
}
const chromium = await chromiumOrSkip();
mkdirSync(outDir, { recursive: true });
const { expect, failed: failures } = checker();

/** `pkm gcode run --report` of an example: the CLI's report. */
function cliReport(args) {
  const dir = mkdtempSync(join(tmpdir(), "pkm-app-test-"));
  const report = join(dir, "report.json");
  const r = spawnSync(pkmBinary, ["gcode", "run", ...args, "--report", report], { encoding: "utf8" });
  if (r.status > 1) throw new Error(`pkm gcode run failed: ${r.stderr}`);
  const json = JSON.parse(readFileSync(report, "utf8"));
  rmSync(dir, { recursive: true, force: true });
  return json;
}

const { server, url } = await startServer(pkmBinary);
const browser = await launch(chromium);
const errors = [];
const foreign = [];
try {
  const page = await watchedPage(browser, new URL(url).origin, { width: 1400, height: 860 }, errors, foreign);
  await page.goto(url);
  await page.evaluate(() => window.pkmApp.ready);

  /** Drawn (non-background) pixels of the canvas in element `id`. */
  const drawn = (id) => drawnPixels(page, id);

  // Machine view.
  await page.waitForTimeout(500);
  expect((await page.textContent("#pose-status")) === "ok", "machine view: the default hexapod at home is ok");
  expect((await drawn("machine-canvas")) > MIN_DRAWN_PIXELS, "machine view: the 3-D canvas has drawn pixels");
  // A pose that overruns the strokes, its closest pair touching: the struts are numbered, the
  // violated ones stay red under the pair's purple, and the status names every violated check.
  const overrun = await page.evaluate(async () => {
    const app = window.pkmApp;
    const mv = app.views.machine;
    const r = await (await fetch("/api/ik", { method: "POST", headers: { "Content-Type": "application/json" },
      body: JSON.stringify({ machine: app.machine.name, poses: [[0, 0, -300, 0, 0, 0]] }) })).json();
    r.rows[0].closest_pair = [0, 1];
    r.rows[0].clearance = 0;
    mv.render({ ...r, joints: app.machine.joints });
    const g = app.scene("machine-canvas").groups[0];
    const out = { labels: g.labels.length, colours: g.struts.map((m) => m.material.color.getHex()), margins: r.rows[0].stroke_margin };
    await mv.update();
    return out;
  });
  expect(overrun.labels === 6 && overrun.margins.every((m, i) => m >= 0 || overrun.colours[i] === 0xd7263d),
    `machine view: numbered struts, violated ones red under the closest pair: ${JSON.stringify(overrun)}`);
  await page.screenshot({ path: join(outDir, "machine.png") });

  // Program view: sphere.ngc as the CLI checks it.
  await page.click("button[data-view=program]");
  await page.waitForTimeout(300);
  expect((await drawn("program-canvas")) > MIN_DRAWN_PIXELS, "program view: the machine is drawn before the first run");
  const ex = join(sourceDir, "examples/gcode");
  const sphere = readFileSync(join(ex, "sphere.ngc"), "utf8");
  const tools = readFileSync(join(ex, "tools.tbl"), "utf8");
  const api = await page.evaluate(async ([text, tbl]) => {
    const v = window.pkmApp.views.program;
    v.setProgram(text);
    v.toolTable = tbl;
    const r = await v.run();
    return r && { checks: r.checks, ok: r.ok, points: r.points };
  }, [sphere, tools]);
  const cli = cliReport([join(ex, "sphere.ngc"), "--machine", "hexapod-default", "--tool-table", join(ex, "tools.tbl")]);
  expect(api && JSON.stringify(api.checks) === JSON.stringify(cli.checks) && api.points === cli.points,
    "program view: sphere.ngc's check results equal the CLI's");
  expect((await drawn("program-canvas")) > MIN_DRAWN_PIXELS, "program view: the machine is drawn along the path");
  await page.screenshot({ path: join(outDir, "program.png") });
  // Opened as a user does: the program and its tool table chosen together; errors would name it.
  await page.evaluate(() => { window.pkmApp.views.program.toolTable = ""; });
  await page.setInputFiles("#open-ngc", [join(ex, "sphere.ngc"), join(ex, "tools.tbl")]);
  // The page reads the chosen files asynchronously: the run starts once both are in.
  await page.waitForFunction(() => window.pkmApp.views.program.fileName === "sphere.ngc" && window.pkmApp.views.program.toolTable.length > 0);
  const opened = await page.evaluate(async () => {
    const v = window.pkmApp.views.program;
    const r = await v.run();
    return { ok: r && r.ok, name: v.fileName, tools: v.toolTable.length > 0 };
  });
  expect(opened.ok === true && opened.name === "sphere.ngc" && opened.tools,
    `program view: sphere.ngc opened with its tools.tbl runs: ${JSON.stringify(opened)}`);

  // A stroke violation: listed, and a click selects its line.
  await page.evaluate(async () => {
    const v = window.pkmApp.views.program;
    v.setProgram("G21 G90\nG0 X0 Y0 Z200\nF600\nG1 Z100\nG1 Z-300\nM2\n");
    await v.run();
  });
  const items = await page.$$("#program-results ol.violations li");
  expect(items.length > 0, "program view: the stroke violation is listed");
  // One entry per line and check (the move violates at many points), at its worst point.
  const listed = await page.evaluate(() => {
    const v = window.pkmApp.views.program;
    const keys = [...document.querySelectorAll("#program-results ol.violations li")].map((li) => li.textContent.split(" ").slice(0, 3).join(" "));
    return { keys, raw: v.sim.result.violations.length };
  });
  expect(new Set(listed.keys).size === listed.keys.length && listed.raw > listed.keys.length,
    `program view: ${listed.raw} violated points listed as ${listed.keys.length} entries, one per line and check`);
  if (items.length) {
    expect((await items[0].textContent()).includes("stroke"), "program view: the first violation is the stroke");
    await items[0].click();
    const line = await page.evaluate(() => {
      const ed = window.pkmApp.views.program.editor;
      return ed.state.doc.lineAt(ed.state.selection.main.head).number;
    });
    expect(line === 5, `program view: clicking the violation selects line 5 (got ${line})`);
    // The animation goes to the worst point of the line (the lowest z), not its first moment.
    const z = await page.evaluate(() => {
      const sim = window.pkmApp.views.program.sim;
      const p = sim.result.path;
      const t = Number(sim.root.querySelector(".scrub").value);
      const k = p.t.findIndex((x) => x >= t - 1e-9);
      return { z: p.pose[k][2], lowest: Math.min(...p.pose.map((q) => q[2])) };
    });
    expect(Math.abs(z.z - z.lowest) < 1e-6, `program view: the click goes to the worst moment (z ${z.z}, lowest ${z.lowest})`);
  }
  // A program error shows at its line (the 422 it answers is expected).
  const before = errors.length;
  const error = await page.evaluate(async () => {
    const v = window.pkmApp.views.program;
    v.setProgram("G0 X0 Y0 Z200\nG1 X1 Q2 F600\n");
    await v.run();
    return {
      text: document.querySelector("#program-error").textContent,
      stale: v.sim.result !== null || document.querySelector("#program-results .summary").textContent !== "" ||
        document.querySelectorAll("#program-results ol.violations li").length > 0,
    };
  });
  expect(error.text.includes("sphere.ngc:2"), `program view: an error names the opened file and its line (${error.text})`);
  expect(!error.stale, "program view: after an error the previous program's results are gone");
  errors.splice(before, errors.length - before, ...errors.slice(before).filter((e) => !e.includes("422")));

  // Blocks view: a program built from blocks (makeTestBlock: a block with its fields, drawn).
  await page.click("button[data-view=blocks]");
  await page.evaluate(() => {
    window.makeTestBlock = (ws, type, fields) => {
      const b = ws.newBlock(type);
      for (const [k, val] of Object.entries(fields)) b.setFieldValue(val, k);
      b.initSvg();
      b.render();
      return b;
    };
  });
  const blocks = await page.evaluate(async () => {
    const v = window.pkmApp.views.blocks;
    const ws = v.workspace;
    ws.clear();
    const make = (type, fields) => window.makeTestBlock(ws, type, fields);
    const feed = make("pkm_feed", { F: 500 });
    const rapid = make("pkm_rapid", { X: 0, Y: 0, Z: 230 });
    const sphere = make("pkm_sphere", { R: 10, X: 0, Y: 0, Z: 190, TR: 2, LEVELS: 2 });
    const down = make("pkm_line", { X: 0, Y: 0, Z: -300 });
    feed.nextConnection.connect(rapid.previousConnection);
    rapid.nextConnection.connect(sphere.previousConnection);
    sphere.nextConnection.connect(down.previousConnection);
    const text = (await v.ready()).text;
    const r = await v.run();
    return { text, warned: v.marked.get(down.id) ?? null, ok: r && r.ok, sphereWarned: v.marked.get(sphere.id) ?? null };
  });
  const expected = [
    "G21 G90 G17 F600 (pkm blocks)", "F500", "G0 X0 Y0 Z230",
    // The sphere as the library makes it (cnc/shapes.hpp, through POST /api/gcode/shape).
    "G0 X12 Y0 Z205", "G1 Z188", "G17 G3 X12 Y0 I-12 J0", "G18 G2 X8.4853 Z196.4853 I-12 K0",
    "G17 G3 X8.4853 Y0 I-8.4853 J0", "G18 G2 X0 Z200 I-8.4853 K-8.4853", "G17 G0 Z205",
    "G1 X0 Y0 Z-300", "M2", ""].join("\n");
  expect(blocks.text === expected, `blocks view: the generated G-code is the expected program\n${blocks.text}`);
  expect(blocks.ok === false && !!blocks.warned, "blocks view: the block that leaves the stroke is marked");
  expect(!blocks.sphereWarned, "blocks view: the sphere block is not marked");
  expect((await drawn("blocks-canvas")) > MIN_DRAWN_PIXELS, "blocks view: the simulator draws the machine");
  await page.screenshot({ path: join(outDir, "blocks.png") });
  // The violation fixed (the last move ends above the part) and the program exported as .ngc.
  const fixed = await page.evaluate(async () => {
    const v = window.pkmApp.views.blocks;
    const last = v.workspace.getTopBlocks(true)[0].getDescendants(true).at(-1);
    last.setFieldValue(230, "Z");
    const r = await v.run();
    return r && r.ok;
  });
  expect(fixed === true, "blocks view: with the move fixed every check passes");
  const [download] = await Promise.all([page.waitForEvent("download"), page.click("#blocks-export")]);
  const exported = readFileSync(await download.path(), "utf8");
  expect(download.suggestedFilename() === "blocks.ngc" && exported.endsWith("G1 X0 Y0 Z230\nM2\n"),
    "blocks view: the program exports as .ngc");
  // Cutter compensation and a subroutine called with arguments, from blocks: the contour runs.
  const comp = await page.evaluate(async () => {
    const v = window.pkmApp.views.blocks;
    const ws = v.workspace;
    ws.clear();
    const make = (type, fields) => window.makeTestBlock(ws, type, fields);
    const chain = (...bs) => bs.reduce((a, b) => (a.nextConnection.connect(b.previousConnection), b));
    const sub = make("pkm_sub", { NAME: "corner" });
    sub.moveBy(20, 300);
    sub.getInput("DO").connection.connect(make("pkm_param", { G: "G1", PX: 1, PY: 2, PZ: 3 }).previousConnection);
    const first = make("pkm_rapid", { X: -20, Y: -20, Z: 230 });
    chain(first, make("pkm_line", { X: -20, Y: -20, Z: 200 }), make("pkm_comp", { SIDE: "G41.1", D: 6 }),
      make("pkm_line", { X: 0, Y: 0, Z: 200 }), make("pkm_call_args", { NAME: "corner", ARGS: "20 0 200" }),
      make("pkm_call_args", { NAME: "corner", ARGS: "20, 20, 200" }), make("pkm_line", { X: 0, Y: 20, Z: 200 }),
      make("pkm_line", { X: 0, Y: 0, Z: 200 }), make("pkm_comp", { SIDE: "G40", D: 0 }), make("pkm_line", { X: -20, Y: -20, Z: 230 }));
    const text = (await v.ready()).text;
    const r = await v.run();
    return { text, ok: r && r.ok };
  });
  expect(comp.ok === true && comp.text.includes("G41.1 D6\nG1 X0 Y0 Z200\no<corner> call [20] [0] [200]\n") &&
    comp.text.includes("o<corner> sub\nG1 X#1 Y#2 Z#3\no<corner> endsub") && comp.text.includes("G40\nG1 X-20 Y-20 Z230"),
    `blocks view: cutter compensation and a call with arguments run\n${JSON.stringify(comp)}`);
  await page.screenshot({ path: join(outDir, "blocks-comp.png") });
  // The arc block as the palette makes it is valid after any move: a full circle about its centre.
  const arc = await page.evaluate(async () => {
    const v = window.pkmApp.views.blocks;
    const ws = v.workspace;
    ws.clear();
    const palette = ws.options.languageTree.contents.flatMap((c) => c.contents || []);
    const fields = palette.find((b) => b.type === "pkm_arc").fields || {};
    const make = (type, f) => window.makeTestBlock(ws, type, f);
    const chain = (...bs) => bs.reduce((a, b) => (a.nextConnection.connect(b.previousConnection), b));
    chain(make("pkm_feed", { F: 500 }), make("pkm_rapid", { X: 30, Y: 7, Z: 200 }), make("pkm_arc", fields));
    const text = (await v.ready()).text;
    const r = await v.run();
    return { text, ok: r && r.ok };
  });
  expect(arc.ok === true && arc.text.includes("G0 X30 Y7 Z200\nG2 I10 J0\n"),
    `blocks view: the palette's arc block runs after any move\n${JSON.stringify(arc)}`);
  // Messages show under the header, inside the window at 1,366 px wide.
  await page.setViewportSize({ width: 1366, height: 768 });
  const shown = await page.evaluate(async () => {
    await window.pkmApp.upload([new File(["[TRAJ]\n"], "alone.ini")]);
    const box = document.querySelector("#message").getBoundingClientRect();
    return { text: document.querySelector("#message-text").textContent, left: box.left, right: box.right, top: box.top, hidden: document.querySelector("#message").hidden };
  });
  expect(!shown.hidden && shown.left >= 0 && shown.right <= 1366 && shown.top < 120 && shown.text.includes("alone.ini"),
    `an error message is shown inside the window: ${JSON.stringify(shown)}`);
  await page.screenshot({ path: join(outDir, "message.png") });
  await page.click("#message-close");
  await page.setViewportSize({ width: 1400, height: 860 });

  // The Exechon: drawn at home, and its example program runs.
  await page.click("button[data-view=machine]");
  await page.selectOption("#machine", "mxt700s-like");
  await page.waitForFunction(() => document.body.dataset.machine === "mxt700s-like");
  await page.waitForTimeout(500);
  expect((await page.textContent("#pose-status")) === "ok", "machine view: the Exechon at home is ok");
  expect((await drawn("machine-canvas")) > MIN_DRAWN_PIXELS, "machine view: the Exechon is drawn");
  expect((await page.evaluate(() => window.pkmApp.machine.drawing.carriage.length)) === 2,
    "machine view: the hybrid machine's X2/Y2 carriage is drawn from its split");
  await page.screenshot({ path: join(outDir, "exechon.png") });
  await page.click("button[data-view=program]");
  const exechon = await page.evaluate(async (text) => {
    const v = window.pkmApp.views.program;
    v.setProgram(text);
    v.toolTable = "";
    const r = await v.run();
    return r && { checks: r.checks };
  }, readFileSync(join(ex, "exechon_contour.ngc"), "utf8"));
  const cliExechon = cliReport([join(ex, "exechon_contour.ngc"), "--machine", "mxt700s-like"]);
  expect(exechon && JSON.stringify(exechon.checks) === JSON.stringify(cliExechon.checks),
    "program view: exechon_contour.ngc's check results equal the CLI's");
  // Blocks on the Exechon: a small sphere near its home tool point.
  await page.click("button[data-view=blocks]");
  const exechonBlocks = await page.evaluate(async () => {
    const v = window.pkmApp.views.blocks;
    const [x, y, z] = window.pkmApp.machine.home;
    v.load({ blocks: { languageVersion: 0, blocks: [{ type: "pkm_rapid", x: 10, y: 10, fields: { X: x, Y: y, Z: z + 30 },
      next: { block: { type: "pkm_sphere", fields: { R: 8, X: x, Y: y, Z: z, TR: 2, LEVELS: 3 } } } }] } });
    const r = await v.run();
    return r && { ok: r.ok, type: r.machine_type, frames: r.frames.rows.length };
  });
  expect(exechonBlocks && exechonBlocks.type === "exechon" && exechonBlocks.ok && exechonBlocks.frames > 10,
    `blocks view: a sphere from blocks runs on the Exechon (${JSON.stringify(exechonBlocks)})`);
  await page.screenshot({ path: join(outDir, "blocks-exechon.png") });

  // Campaign view.
  await page.click("button[data-view=campaign]");
  await page.click("#campaign-run");
  await page.waitForFunction(() => window.pkmApp.views.campaign.finished, null, { timeout: 120000 });
  await page.waitForFunction(() => document.querySelector("#campaign-report").src.includes("/report.html"));
  await page.waitForTimeout(1000);
  const met = (await page.textContent("#campaign-log")).includes("every target met");
  expect(met, "campaign view: the default campaign meets its targets");
  const steps = await page.evaluate(() => [...document.querySelectorAll("#campaign-log li.campaign-step")].map((li) => li.querySelectorAll("tr").length));
  expect(steps.length >= 4 && steps.every((n) => n > 0), `campaign view: each step's results listed as it finished (${JSON.stringify(steps)})`);
  // DevTools may report the streamed POST /api/campaign as aborted (net::ERR_ABORTED) although
  // the page read every event to the end of the stream (the result above arrived): not an error
  // of the page.
  if (met) {
    const streamed = (e) => e.includes("/api/campaign (net::ERR_ABORTED)");
    errors.splice(0, errors.length, ...errors.filter((e) => !streamed(e)));
  }
  await page.screenshot({ path: join(outDir, "campaign.png") });
} catch (e) {
  failures.push(`exception: ${e.stack || e}`);
} finally {
  await browser.close();
  server.kill("SIGINT");
}
expect(errors.length === 0, `no console or page errors ${errors.length ? JSON.stringify(errors) : ""}`);
expect(foreign.length === 0, `no request left 127.0.0.1 ${foreign.length ? JSON.stringify(foreign) : ""}`);
if (failures.length) {
  console.error(`\n${failures.length} failure(s):\n${failures.join("\n")}`);
  process.exit(1);
}
console.log(`all passed; screenshots in ${outDir}`);
