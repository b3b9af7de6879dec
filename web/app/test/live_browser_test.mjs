// Browser test of the page following a running LinuxCNC (docs/linuxcnc.md, "The live machine"),
// driven by tests/linuxcnc/live_browser_test.py, which starts LinuxCNC and `pkm serve --linuxcnc`
// and runs a program on the machine. Over standard input and output the two take turns:
//
//   this test                                     the driver
//   opens URL; waits for the machine "linuxcnc" -> prints "ready"
//                                                 <- runs the program, writes "running"
//   while it runs, samples the page: the drawn machine's joints (pkm's inverse kinematics of
//   LinuxCNC's actual pose) against LinuxCNC's joint feedback (1e-6), the
//   machine moving, the highlighted line = LinuxCNC's executing line, a violation flagged ahead
//   of it -> prints "seen"                        <- puts LinuxCNC in E-stop, writes "estop"
//   the header shows E-stop in red -> screenshot, prints the result, exits 0 (pass) or 1
//
//   node live_browser_test.mjs URL OUT_DIR
//
// Exit 77 (skipped) without chromium or web/app/node_modules.
import { existsSync, mkdirSync } from "node:fs";
import { createInterface } from "node:readline";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const CHROMIUM = process.env.PKM_CHROMIUM || "/usr/bin/chromium";
const JOINT_TOL = 1e-6; // inch: the drawn machine's joints against those LinuxCNC commands
const here = dirname(fileURLToPath(import.meta.url));
const [url, outDir] = process.argv.slice(2);
if (!existsSync(CHROMIUM) || !existsSync(join(here, "../node_modules/playwright-core"))) {
  console.log(`SKIP: ${CHROMIUM} or web/app/node_modules missing (scripts/setup.sh)`);
  process.exit(77);
}
const { chromium } = await import("playwright-core");
mkdirSync(outDir, { recursive: true });

const lines = createInterface({ input: process.stdin });
const inbox = [];
let waiting = null;
lines.on("line", (l) => (waiting ? (waiting(l), (waiting = null)) : inbox.push(l)));
const next = () => (inbox.length ? Promise.resolve(inbox.shift()) : new Promise((r) => (waiting = r)));

const failures = [];
const expect = (ok, what) => {
  if (!ok) failures.push(what);
  console.error(`${ok ? "ok  " : "FAIL"} ${what}`);
};
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

/** What the page shows now: its last record, the drawn row, the marked line and the flag. */
const sample = (page) =>
  page.evaluate(() => {
    const app = window.pkmApp;
    const j = app.follower.last;
    const marked = document.querySelector(".cm-live-line");
    const ahead = document.querySelector("#live-ahead");
    return {
      machine: app.machine?.name,
      state: j?.state,
      line: j?.status?.executing_line ?? 0,
      lcnc: j?.status?.joints_actual,
      drawn: app.views.machine.liveRow?.joints,
      tool: app.views.machine.liveRow?.tool_point,
      marked: marked ? marked.textContent : null,
      program: app.views.program.program().split("\n"),
      ahead: ahead?.dataset.line ? Number(ahead.dataset.line) : null,
      aheadText: ahead?.textContent ?? "",
      header: document.querySelector("#live-status").textContent,
      headerClass: document.querySelector("#live-status").className,
    };
  });

const browser = await chromium.launch({ executablePath: CHROMIUM, args: ["--no-sandbox", "--disable-gpu"] });
const errors = [];
try {
  const page = await browser.newPage({ viewport: { width: 1366, height: 768 } });
  page.on("pageerror", (e) => errors.push(`page error: ${e.message}`));
  page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
  await page.goto(url);
  await page.evaluate(() => window.pkmApp.ready);
  await page.waitForFunction(() => window.pkmApp.machine?.name === "linuxcnc", null, { timeout: 20000 });
  console.log("ready");
  expect((await next()) === "running", "the driver started the program");

  let worst = 0, moved = false, flaggedAhead = null, marks = new Set(), lastTool = null, running = 0;
  const deadline = Date.now() + 60000;
  while (Date.now() < deadline) {
    const s = await sample(page);
    if (s.state === "running" && s.lcnc && s.drawn) {
      running++;
      worst = Math.max(worst, ...s.drawn.map((q, i) => Math.abs(q - s.lcnc[i])));
      if (lastTool && s.tool.some((v, i) => Math.abs(v - lastTool[i]) > 1e-3)) moved = true;
      lastTool = s.tool;
      if (s.line > 0 && s.marked !== null && s.marked === s.program[s.line - 1]) marks.add(s.line);
      if (s.ahead !== null && s.line > 0 && s.ahead > s.line) flaggedAhead ??= { at: s.line, ahead: s.ahead, text: s.aheadText };
    }
    if (running > 20 && moved && marks.size >= 3 && flaggedAhead) break;
    await sleep(100);
  }
  await page.screenshot({ path: join(outDir, "live-running.png") });
  await page.click("#views button[data-view=program]");
  await sleep(300);
  await page.screenshot({ path: join(outDir, "live-program.png") });
  expect(running > 20, `the page followed the running program (${running} samples)`);
  expect(worst <= JOINT_TOL, `drawn joints = LinuxCNC's joint feedback within ${JOINT_TOL} (worst ${worst.toExponential(2)})`);
  expect(moved, "the 3-D machine moved with LinuxCNC");
  expect(marks.size >= 3, `the executing line was highlighted (lines ${[...marks].join(", ")})`);
  expect(flaggedAhead !== null, `a violation flagged ahead of the executing line: ${JSON.stringify(flaggedAhead)}`);
  console.log("seen");

  expect((await next()) === "estop", "the driver put LinuxCNC in E-stop");
  let estop = null;
  for (let k = 0; k < 50 && !estop; ++k) {
    const s = await sample(page);
    if (s.state === "estop") estop = s;
    else await sleep(100);
  }
  await page.screenshot({ path: join(outDir, "live-estop.png") });
  expect(estop !== null && estop.headerClass === "live-bad" && /estop/.test(estop.header), `E-stop shown at once in red: ${estop?.header}`);
  expect(errors.length === 0, `no console or page error${errors.length ? ": " + errors.join("; ") : ""}`);
} catch (e) {
  failures.push(`exception: ${e.stack || e}`);
} finally {
  await browser.close();
}
console.log(failures.length ? `FAIL ${failures.length}` : "PASS");
process.exit(failures.length ? 1 : 0);
