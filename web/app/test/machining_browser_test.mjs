// Browser test of the machining preview (docs/machining.md) at 1,366 x 768: examples/gcode/
// sphere.ngc and its tools.tbl opened as a user does, the preview switched on with a box of
// stock, Run with the mouse: the stock is drawn, the removed volume equals the CLI's, no
// collision; playing at 20x its frames per second are measured; the finished part is shown
// alone; a rapid through the stock is listed and a click on it selects its line. Screenshots and
// machining-fps.json (the measured rates) go to OUT_DIR.
//
//   node machining_browser_test.mjs PKM_BINARY SOURCE_DIR OUT_DIR
//
// Exit codes: 0 pass, 1 fail, 77 skipped (no chromium or no web/app/node_modules).
import { spawnSync } from "node:child_process";
import { mkdirSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { checker, chromiumOrSkip, drawnPixels, launch, startServer, watchedPage } from "./harness.mjs";

const MIN_DRAWN_PIXELS = 2000;
const [pkmBinary, sourceDir, outDir] = process.argv.slice(2);
if (!pkmBinary || !sourceDir || !outDir) {
  console.error("usage: machining_browser_test.mjs PKM_BINARY SOURCE_DIR OUT_DIR");
  process.exit(1);
}
const chromium = await chromiumOrSkip();
mkdirSync(outDir, { recursive: true });
const { expect, failed } = checker();
const ex = join(sourceDir, "examples/gcode");
const BOX = "25,15,-10,75,65,20";

/** The CLI's removed volume for the same stock (mm³), from its text report. */
function cliRemoved(cell) {
  const r = spawnSync(pkmBinary, ["gcode", "run", join(ex, "sphere.ngc"), "--stock", `box:${BOX}`, "--stock-cell", String(cell)], { encoding: "utf8" });
  const m = /removed ([\d.]+) mm3/.exec(r.stdout);
  return m ? Number(m[1]) : NaN;
}

const { server, url } = await startServer(pkmBinary);
const browser = await launch(chromium);
const errors = [];
const foreign = [];
try {
  const page = await watchedPage(browser, new URL(url).origin, { width: 1366, height: 768 }, errors, foreign);
  await page.goto(url);
  await page.evaluate(() => window.pkmApp.ready);
  await page.click("button[data-view=program]");
  await page.setInputFiles("#open-ngc", [join(ex, "sphere.ngc"), join(ex, "tools.tbl")]);
  await page.waitForFunction(() => window.pkmApp.views.program.fileName === "sphere.ngc" && window.pkmApp.views.program.toolTable.length > 0);
  await page.check("#program-results .mach-on");
  await page.selectOption("#program-results .mach-stock", "box");
  await page.fill("#program-results .mach-dims", BOX);
  await page.click("#run");
  await page.waitForSelector("#program-results .machining-summary", { timeout: 60000 });
  const shown = await page.evaluate(() => {
    const sim = window.pkmApp.views.program.sim;
    const m = sim.result.machining;
    return { summary: document.querySelector("#program-results .machining-summary").textContent, cell: m.cell, removed: m.initial_volume_mm3 - m.final_volume_mm3, events: m.events.length, frames: m.frames.length, seconds: m.seconds, cells: m.nx * m.ny, mesh: !!sim.stockView.mesh, vertices: sim.stockView.mesh.geometry.attributes.position.count };
  });
  expect(shown.mesh && shown.vertices === shown.cells, `the stock is drawn as a ${shown.vertices}-vertex surface`);
  expect(shown.summary.includes("no collision") && shown.events === 0, `no collision on the shipped sphere (${shown.summary})`);
  const cli = cliRemoved(shown.cell);
  expect(Math.abs(shown.removed - cli) < 0.05 + 1e-6 * cli, `the page's removed volume ${shown.removed.toFixed(1)} mm3 equals the CLI's ${cli} mm3`);
  expect(shown.frames > 100, `the removal is animated in ${shown.frames} frames`);
  expect((await drawnPixels(page, "program-canvas")) > MIN_DRAWN_PIXELS, "the 3-D area is drawn");
  await page.screenshot({ path: join(outDir, "machining-start.png") });

  // Play at 20x: frames per second while the stock changes.
  const fps = await page.evaluate(async () => {
    const sim = window.pkmApp.views.program.sim;
    sim.root.querySelector(".speed").value = "20";
    sim.seek(0);
    let frames = 0;
    let running = true;
    const count = () => {
      ++frames;
      if (running) requestAnimationFrame(count);
    };
    requestAnimationFrame(count);
    const start = performance.now();
    sim.toggle();
    await new Promise((resolve) => setTimeout(resolve, 4000));
    running = false;
    if (sim.playing) sim.toggle();
    const seconds = (performance.now() - start) / 1000;
    return { fps: frames / seconds, applied: sim.stockView.applied, time: sim.time };
  });
  expect(fps.fps > 4 && fps.applied > 10, `playing at 20x: ${fps.fps.toFixed(1)} frames/s, ${fps.applied} stock frames applied by t ${fps.time.toFixed(1)} s`);
  writeFileSync(join(outDir, "machining-fps.json"), JSON.stringify({ ...fps, removal_s: shown.seconds, viewport: "1366x768", renderer: "headless chromium, software GL" }, null, 1));
  await page.click("#program-results .mach-zoom");
  await page.screenshot({ path: join(outDir, "machining-playing.png") });
  await page.click("#program-results .mach-part");
  const part = await page.evaluate(() => {
    const sim = window.pkmApp.views.program.sim;
    const h = sim.stockView.heights, f = sim.stockView.finished;
    return { same: h.every((x, i) => x === f[i]), machineHidden: !sim.app.scene("program-canvas").groups[0].root.visible };
  });
  expect(part.same && part.machineHidden, "finished part: the final heights, the machine hidden");
  await page.screenshot({ path: join(outDir, "machining-part.png") });

  // A rapid through the stock: listed, and a click selects its line.
  await page.evaluate(() => window.pkmApp.views.program.setProgram("G21 G90\nG0 X0 Y0 Z210\nG1 Z200 F300\nG1 X40\nG1 Z199\nG1 X0\nG0 X20 Y5\nM2\n"));
  await page.selectOption("#program-results .mach-stock", "auto");
  await page.click("#run");
  await page.waitForSelector("#program-results li.collision", { timeout: 60000 });
  const item = await page.textContent("#program-results li.collision");
  expect(item.startsWith("line 7: rapid move through the stock, 1.000 mm deep"), `the rapid is listed: ${item}`);
  await page.click("#program-results li.collision");
  const line = await page.evaluate(() => {
    const v = window.pkmApp.views.program;
    return v.editor.state.doc.lineAt(v.editor.state.selection.main.head).number;
  });
  expect(line === 7, `clicking the collision selects line 7 (got ${line})`);
  // Bad stock: the server's message shows where the user looks.
  await page.selectOption("#program-results .mach-stock", "box");
  await page.fill("#program-results .mach-dims", "1,2,3");
  await page.click("#run");
  await page.waitForFunction(() => document.querySelector("#program-error").textContent.length > 0);
  const bad = await page.textContent("#program-error");
  expect(bad.includes("machining.box"), `a box of three numbers is refused with a message (${bad})`);
  // The refused run's 400 is expected: the browser logs it twice (response, console).
  errors.splice(0, errors.length, ...errors.filter((e) => !e.startsWith("HTTP 400") && !e.includes("status of 400")));
  await page.screenshot({ path: join(outDir, "machining-collision.png") });
} finally {
  await browser.close();
  server.kill();
}
expect(errors.length === 0, `no console or page errors ${errors.length ? JSON.stringify(errors) : ""}`);
expect(foreign.length === 0, `no request left 127.0.0.1 ${foreign.length ? JSON.stringify(foreign) : ""}`);
if (failed.length) {
  console.log(`${failed.length} check(s) failed`);
  process.exit(1);
}
console.log("all machining preview checks passed");
