// What the browser tests of `pkm serve` share: the skip rule, the server on a free port, headless
// Chromium, a page that records console errors and requests leaving 127.0.0.1, and a count of a
// canvas's drawn pixels.
import { spawn } from "node:child_process";
import { existsSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

export const SKIP = 77;
const CHROMIUM = process.env.PKM_CHROMIUM || "/usr/bin/chromium";
const here = dirname(fileURLToPath(import.meta.url));

/** Exits with SKIP when Chromium or playwright-core is missing; else returns playwright's chromium. */
export async function chromiumOrSkip() {
  if (!existsSync(CHROMIUM) || !existsSync(join(here, "../node_modules/playwright-core"))) {
    console.log(`SKIP: ${CHROMIUM} or web/app/node_modules missing (scripts/setup.sh)`);
    process.exit(SKIP);
  }
  return (await import("playwright-core")).chromium;
}

/** A checker: expect(ok, what) prints and records; failures() lists what failed. */
export function checker() {
  const failed = [];
  const expect = (ok, what) => {
    if (!ok) failed.push(what);
    console.log(`${ok ? "ok  " : "FAIL"} ${what}`);
  };
  return { expect, failed };
}

/** `pkm serve --port 0 ...args`: the process and its URL (with the launch's token). */
export async function startServer(pkmBinary, args = []) {
  const server = spawn(pkmBinary, ["serve", "--port", "0", ...args], { stdio: ["ignore", "pipe", "inherit"] });
  const url = await new Promise((resolve, reject) => {
    server.stdout.on("data", (d) => {
      const m = /pkm: serving (http:\/\/127\.0\.0\.1:\d+\/\S*)/.exec(String(d));
      if (m) resolve(m[1]);
    });
    server.on("exit", (code) => reject(new Error(`pkm serve exited ${code}`)));
  });
  return { server, url };
}

/** Headless Chromium as every browser test runs it. */
export function launch(chromium) {
  return chromium.launch({
    executablePath: CHROMIUM,
    args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
      "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });
}

/** A page of `browser` whose console errors and foreign requests land in `errors`, `foreign`. */
export async function watchedPage(browser, origin, viewport, errors, foreign) {
  const page = await browser.newPage({ viewport });
  page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
  page.on("pageerror", (e) => errors.push(`page error: ${e.message}`));
  page.on("requestfailed", (r) => errors.push(`request failed: ${r.url()} (${r.failure()?.errorText})`));
  page.on("response", (r) => r.status() >= 400 && errors.push(`HTTP ${r.status()} ${r.url()}`));
  page.on("request", (r) => {
    const u = r.url();
    if (!u.startsWith(origin) && !u.startsWith("blob:") && !u.startsWith("data:")) foreign.push(u);
  });
  return page;
}

/** Drawn (non-background) pixels of the canvas in element `id` of `page`. */
export function drawnPixels(page, id) {
  return page.evaluate((id) => {
    const src = document.querySelector(`#${id} canvas`);
    const c = document.createElement("canvas");
    c.width = src.width;
    c.height = src.height;
    const g = c.getContext("2d");
    g.drawImage(src, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - 247) + Math.abs(d[i + 1] - 248) + Math.abs(d[i + 2] - 250) > 30) ++n;
    return n;
  }, id);
}
