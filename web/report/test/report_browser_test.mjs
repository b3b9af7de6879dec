// Browser test of the pkm HTML report (docs/report.md): opens a report in headless Chromium
// (Debian's /usr/bin/chromium driven by playwright-core) and fails on any console error, page
// error, request leaving the file, or a plot of the report data without a drawn chart.
//
//   node report_browser_test.mjs REPORT.html
//   node report_browser_test.mjs --pkm PKM_BINARY --data DATA.json   (renders it first)
//   ... --screenshot PAGE.png   (also saves a full-page screenshot, to look at the page)
//
// Exit codes: 0 pass, 1 fail, 77 skipped (no chromium or no web/report/node_modules).
import { spawnSync } from "node:child_process";
import { existsSync, mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { pathToFileURL } from "node:url";

const SKIP = 77;
const CHROMIUM = process.env.PKM_CHROMIUM || "/usr/bin/chromium";
// Axes, grid and text are grey; the data (series colours, viridis markers) is saturated. A chart
// whose data was drawn has far more saturated canvas pixels than this.
const MIN_DATA_PIXELS = 100;
const SATURATION = 60; // max(r,g,b) - min(r,g,b) of a data pixel

function usage() {
  console.error(
    "usage: report_browser_test.mjs REPORT.html | --pkm PKM --data DATA.json [--screenshot PNG]");
  process.exit(1);
}

function parseArgs(argv) {
  const a = { report: null, pkm: null, data: null, screenshot: null };
  for (let i = 0; i < argv.length; i++) {
    if (argv[i] === "--pkm") a.pkm = argv[++i];
    else if (argv[i] === "--data") a.data = argv[++i];
    else if (argv[i] === "--screenshot") a.screenshot = argv[++i];
    else if (!a.report) a.report = argv[i];
    else usage();
  }
  if (!a.report && !(a.pkm && a.data)) usage();
  return a;
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  if (!existsSync(CHROMIUM)) {
    console.log(`SKIP: ${CHROMIUM} not found (scripts/setup.sh installs chromium)`);
    return SKIP;
  }
  let chromium;
  try {
    ({ chromium } = await import("playwright-core"));
  } catch {
    console.log("SKIP: playwright-core not installed (run scripts/setup.sh: npm ci in web/report)");
    return SKIP;
  }
  let tmp = null;
  let report = args.report;
  if (!report) {
    tmp = mkdtempSync(join(tmpdir(), "pkm-report-"));
    report = join(tmp, "report.html");
    const r = spawnSync(args.pkm, ["report", "render", args.data, "--out", report], {
      encoding: "utf8",
    });
    if (r.status !== 0) {
      console.error(`FAIL: pkm report render exited ${r.status}: ${r.stderr}`);
      return 1;
    }
  }
  const failures = [];
  const browser = await chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    args: ["--no-sandbox", "--disable-gpu"],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
    page.on("console", (m) => {
      if (m.type() === "error") failures.push(`console error: ${m.text()}`);
    });
    page.on("pageerror", (e) => failures.push(`page error: ${e.message}`));
    page.on("request", (r) => {
      if (!r.url().startsWith("file:") && !r.url().startsWith("data:"))
        failures.push(`external request (report must be self-contained): ${r.url()}`);
    });
    await page.goto(pathToFileURL(resolve(report)).href, { waitUntil: "load" });
    await page
      .waitForFunction(() => document.body.dataset.rendered, null, { timeout: 15000 })
      .catch(() => failures.push("render.js did not finish (body[data-rendered] never set)"));
    const state = await page.evaluate(([minInk, sat]) => {
      const data = JSON.parse(document.getElementById("pkm-report-data").textContent);
      const plots = data.plots.map((p) => {
        const fig = document.querySelector(`figure[data-plot-id="${CSS.escape(p.id)}"]`);
        const canvas = fig ? fig.querySelector("canvas") : null;
        let inked = 0;
        if (canvas && canvas.width > 0 && canvas.height > 0) {
          const px = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data;
          for (let i = 0; i < px.length; i += 4) {
            const hi = Math.max(px[i], px[i + 1], px[i + 2]);
            const lo = Math.min(px[i], px[i + 1], px[i + 2]);
            if (px[i + 3] > 0 && hi - lo > sat) inked++;
          }
        }
        const box = canvas ? canvas.getBoundingClientRect() : { width: 0, height: 0 };
        return { id: p.id, kind: p.kind, figure: !!fig, canvas: !!canvas,
          width: box.width, height: box.height, inked, ok: inked >= minInk };
      });
      return { rendered: document.body.dataset.rendered, plots,
        figures: document.querySelectorAll("figure[data-plot-id]").length };
    }, [MIN_DATA_PIXELS, SATURATION]);
    if (state.rendered !== "ok") failures.push(`render.js reported: ${state.rendered}`);
    if (state.plots.length === 0) failures.push("the report data has no plots");
    if (state.figures !== state.plots.length)
      failures.push(`${state.figures} figures in the page for ${state.plots.length} plots`);
    for (const p of state.plots) {
      if (!p.figure) failures.push(`plot ${p.id}: no <figure data-plot-id>`);
      else if (!p.canvas) failures.push(`plot ${p.id}: no chart canvas`);
      else if (!(p.width > 0 && p.height > 0)) failures.push(`plot ${p.id}: chart has zero size`);
      else if (!p.ok) failures.push(`plot ${p.id}: no data drawn (${p.inked} data-coloured pixels)`);
    }
    // Hover every chart so that the cursor/legend code runs too (errors are caught above).
    for (const p of state.plots) {
      const over = page.locator(`figure[data-plot-id="${p.id}"] .u-over`);
      if ((await over.count()) === 1) await over.hover({ timeout: 5000 }).catch(() => {});
    }
    await page.waitForTimeout(100);
    if (args.screenshot) await page.screenshot({ path: args.screenshot, fullPage: true });
    for (const p of state.plots)
      console.log(`plot ${p.id} (${p.kind}): ${Math.round(p.width)}x${Math.round(p.height)} px, ` +
        `${p.inked} data-coloured canvas pixels`);
  } finally {
    await browser.close();
    if (tmp) rmSync(tmp, { recursive: true, force: true });
  }
  if (failures.length > 0) {
    for (const f of failures) console.error(`FAIL: ${f}`);
    return 1;
  }
  console.log(`PASS: ${report}`);
  return 0;
}

main().then(
  (code) => process.exit(code),
  (e) => {
    console.error(`FAIL: ${e && e.stack ? e.stack : e}`);
    process.exit(1);
  }
);
