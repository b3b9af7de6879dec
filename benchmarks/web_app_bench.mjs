// The web application's speed (docs/web.md "Performance"): for the example programs and a
// 100,000-line program, the time from Run to the first animated frame (the API's run, the transfer,
// the page's drawing), the response size, and the frame rate while the animation plays, in headless
// Chromium against `pkm serve`. Not a test: figures for the notes.
//
//   node benchmarks/web_app_bench.mjs PKM_BINARY SOURCE_DIR
import { spawn } from "node:child_process";
import { readFileSync } from "node:fs";
import { createRequire } from "node:module";
import { join } from "node:path";

const [pkm, src] = process.argv.slice(2);
const require = createRequire(join(src, "web/app/package.json"));
const { chromium } = require("playwright-core");

function bigProgram(lines) {
  const out = ["G21 G90 G0 X0 Y0 Z200", "F3000"];
  for (let i = 0; out.length < lines - 1; ++i) {
    const a = (i * 2 * Math.PI) / 400;
    out.push(`G1 X${(60 * Math.cos(a)).toFixed(3)} Y${(60 * Math.sin(a)).toFixed(3)} Z${(200 - (i % 2000) * 0.01).toFixed(3)}`);
  }
  out.push("M2");
  return out.join("\n") + "\n";
}

const server = spawn(pkm, ["serve", "--port", "0"], { stdio: ["ignore", "pipe", "inherit"] });
const url = await new Promise((ok) => server.stdout.on("data", (d) => { const m = /serving (\S+)/.exec(String(d)); if (m) ok(m[1]); }));
const browser = await chromium.launch({ executablePath: "/usr/bin/chromium", args: ["--no-sandbox", "--disable-gpu", "--disable-background-networking"] });
const page = await browser.newPage({ viewport: { width: 1400, height: 860 } });
await page.goto(url);
await page.evaluate(() => window.pkmApp.ready);
await page.click("button[data-view=program]");
const ex = join(src, "examples/gcode");
const cases = [
  ["sphere.ngc", "hexapod-default", readFileSync(join(ex, "sphere.ngc"), "utf8"), readFileSync(join(ex, "tools.tbl"), "utf8")],
  ["hexapod_contour.ngc", "hexapod-default", readFileSync(join(ex, "hexapod_contour.ngc"), "utf8"), ""],
  ["exechon_contour.ngc", "mxt700s-like", readFileSync(join(ex, "exechon_contour.ngc"), "utf8"), ""],
  ["100,000 lines", "hexapod-default", bigProgram(100000), ""],
];
for (const [name, machine, text, tools] of cases) {
  await page.selectOption("#machine", machine);
  await page.waitForFunction((m) => document.body.dataset.machine === m, machine);
  const r = await page.evaluate(async ([text, tools]) => {
    const v = window.pkmApp.views.program;
    v.setProgram(text);
    v.toolTable = tools;
    const t0 = performance.now();
    const res = await v.run();
    await new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok)));
    const firstFrame = performance.now() - t0;
    const entry = performance.getEntriesByType("resource").filter((e) => e.name.endsWith("/api/gcode/run")).at(-1);
    // Play for 3 s at 20x and count the frames drawn.
    // Play at a speed that lasts about 3 s and count the frames drawn while it plays.
    let frames = 0;
    const end = res.frames.t.at(-1);
    v.sim.root.querySelector(".speed").innerHTML = `<option>${end / 3}</option>`;
    const start = performance.now();
    let stop = start;
    const count = () => { frames++; stop = performance.now(); if (v.sim.playing) requestAnimationFrame(count); };
    v.sim.toggle();
    requestAnimationFrame(count);
    await new Promise((ok) => setTimeout(ok, 3500));
    if (v.sim.playing) v.sim.toggle();
    return { points: res.points, firstFrame, server: entry.responseStart - entry.requestStart, bytes: entry.encodedBodySize || entry.transferSize, fps: frames / ((stop - start) / 1000) };
  }, [text, tools]);
  console.log(`${name.padEnd(20)} ${String(r.points).padStart(8)} points  run+transfer+first frame ${r.firstFrame.toFixed(0)} ms (server ${r.server.toFixed(0)} ms, ${(r.bytes / 1e6).toFixed(2)} MB)  animation ${r.fps.toFixed(0)} frames/s`);
}
await browser.close();
server.kill("SIGINT");
