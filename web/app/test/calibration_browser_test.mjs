// Browser test of the automated calibration from the page (docs/linuxcnc.md, "Automated
// calibration by constrained motion"), driven by tests/linuxcnc/live_calibration_test.py, which
// starts LinuxCNC with the simulated true machine in its loop and `pkm serve --linuxcnc` as
// LinuxCNC's user. Three routines, as a user would run them with the mouse:
//   1. Start… opens a dialog that says what will move; "Move the machine" starts; progress and
//      stations arrive; after the fit the page asks "Install the calibration?" with the held-out
//      figures; "Keep the configuration" answers; the report arrives, nothing installed.
//   2. Started again, "Stop the machine" during the stations: the routine ends "stopped", and
//      LinuxCNC is idle and still within a second.
//   3. Started again, the page is closed during the stations: the server stops the routine and
//      LinuxCNC's motion within 2 s (the heartbeat), and says nothing runs.
// Screenshots at 1,366 px wide. Prints PASS or FAIL N; exit 0 or 1.
//
//   node calibration_browser_test.mjs URL OUT_DIR STATIONS HOLDOUT
//
// Exit 77 (skipped) without chromium or web/app/node_modules.
import { existsSync, mkdirSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const CHROMIUM = process.env.PKM_CHROMIUM || "/usr/bin/chromium";
const here = dirname(fileURLToPath(import.meta.url));
const [url, outDir, stations, holdout] = process.argv.slice(2);
if (!existsSync(CHROMIUM) || !existsSync(join(here, "../node_modules/playwright-core"))) {
  console.log(`SKIP: ${CHROMIUM} or web/app/node_modules missing (scripts/setup.sh)`);
  process.exit(77);
}
const { chromium } = await import("playwright-core");
mkdirSync(outDir, { recursive: true });
const origin = new URL(url).origin;

const failures = [];
const expect = (ok, what) => {
  if (!ok) failures.push(what);
  console.error(`${ok ? "ok  " : "FAIL"} ${what}`);
};
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const api = async (path) => (await fetch(origin + path)).json();

/** LinuxCNC idle and still, and no routine on the server, within `ms`. */
async function stopped(ms) {
  const deadline = Date.now() + ms;
  while (Date.now() < deadline) {
    const [live, routine] = await Promise.all([api("/api/live"), api("/api/live/calibration")]);
    if (!routine.running && live.status?.interpreter === "idle" && Math.abs(live.status?.velocity ?? 1) < 1e-9) return true;
    await sleep(50);
  }
  return false;
}

async function openPanel(page) {
  await page.goto(url);
  await page.evaluate(() => window.pkmApp.ready);
  try {
    await page.waitForFunction(() => window.pkmApp.machine?.name === "linuxcnc", null, { timeout: 20000 });
  } catch (e) {
    await page.screenshot({ path: join(outDir, "calibration-no-machine.png") });
    throw new Error(`the page did not select LinuxCNC's machine; GET /api/live: ${JSON.stringify(await api("/api/live")).slice(0, 1500)}`);
  }
  await page.click("#livecal summary");
  await page.fill("#livecal-stations", stations);
  await page.fill("#livecal-holdout", holdout);
  await page.fill("#livecal-laser", "");
  await page.fill("#livecal-settle", "0.02");
  await page.fill("#livecal-tolerance", "0.01");
}

async function start(page) {
  await page.click("#livecal-start");
  await page.waitForSelector("#livecal-confirm[open]");
  await page.click("#livecal-go");
}

/** Waits for `n` stations measured (the log's lines). */
const stationsSeen = (page, n, timeout = 60000) =>
  page.waitForFunction((k) => [...document.querySelectorAll("#livecal-log li")].filter((li) => / station /.test(li.textContent)).length >= k, n, { timeout });

const browser = await chromium.launch({ executablePath: CHROMIUM, args: ["--no-sandbox", "--disable-gpu"] });
const errors = [];
let page = null;
try {
  const context = await browser.newContext({ viewport: { width: 1366, height: 768 } });
  page = await context.newPage();
  page.on("pageerror", (e) => errors.push(`page error: ${e.message}`));
  await openPanel(page);
  await page.screenshot({ path: join(outDir, "calibration-panel.png") });

  // 1. The whole routine, the installation declined.
  await page.click("#livecal-start");
  await page.waitForSelector("#livecal-confirm[open]");
  await page.screenshot({ path: join(outDir, "calibration-confirm.png") });
  expect(/Move the machine/.test(await page.textContent("#livecal-confirm")), "Start asks before anything moves");
  await page.click("#livecal-go");
  const started = Date.now();
  await page.waitForFunction(
    () => document.querySelector("#livecal-install").open || !document.body.classList.contains("calibrating"),
    null,
    { timeout: 240000 },
  );
  if (!(await page.evaluate(() => document.querySelector("#livecal-install").open)))
    throw new Error(`the routine ended without asking: ${await page.textContent("#livecal-log")}`);
  await page.screenshot({ path: join(outDir, "calibration-install.png") });
  const figures = await page.textContent("#livecal-figures");
  expect(/held-out gauge residuals/.test(figures), `the page asks with the held-out figures: ${figures.replace(/\s+/g, " ")}`);
  await page.click("#livecal-keep");
  await page.waitForFunction(() => !document.body.classList.contains("calibrating"), null, { timeout: 60000 });
  const report = await page.textContent("#livecal-report");
  const stage = await page.textContent("#livecal-stage");
  await page.screenshot({ path: join(outDir, "calibration-done.png"), fullPage: true });
  expect(/not installed/.test(stage) && report.length > 200, `the result arrives, nothing installed: ${stage}`);
  console.error(`routine from the page: ${((Date.now() - started) / 1000).toFixed(1)} s`);

  // 2. Stop during the stations.
  await start(page);
  await stationsSeen(page, 2);
  await page.click("#livecal-stop");
  await page.waitForFunction(() => !document.body.classList.contains("calibrating"), null, { timeout: 10000 });
  expect(/stopped/.test(await page.textContent("#livecal-stage")), "Stop ends the routine: stopped");
  expect(await stopped(1000), "after Stop, LinuxCNC is idle and still within 1 s");

  // 3. The page goes away during the stations.
  await start(page);
  await stationsSeen(page, 2);
  await page.close();
  expect(await stopped(2000), "with the page closed, the server stops the routine and LinuxCNC within 2 s");
  expect(errors.length === 0, `no page error${errors.length ? ": " + errors.join("; ") : ""}`);
} catch (e) {
  failures.push(`exception: ${e.stack || e}`);
  if (page && !page.isClosed()) {
    await page.screenshot({ path: join(outDir, "calibration-failed.png"), fullPage: true });
    failures.push(`the page's log: ${await page.textContent("#livecal-log")}`);
  }
} finally {
  await browser.close();
}
for (const f of failures) console.error(`FAIL ${f}`);
console.log(failures.length ? `FAIL ${failures.length}` : "PASS");
process.exit(failures.length ? 1 : 0);
