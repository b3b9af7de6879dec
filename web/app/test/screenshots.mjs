// The documentation's screenshots of the page at 1,366 x 768 (docs/web.md): each view as a user
// leaves it after a typical action. Not a test; run it after a change to the page's layout:
//
//   node web/app/test/screenshots.mjs build/bin/pkm . docs/images
import { mkdirSync } from "node:fs";
import { join } from "node:path";
import { chromiumOrSkip, launch, startServer, watchedPage } from "./harness.mjs";

const [pkmBinary, sourceDir, outDir] = process.argv.slice(2);
if (!pkmBinary || !sourceDir || !outDir) {
  console.error("usage: screenshots.mjs PKM_BINARY SOURCE_DIR OUT_DIR");
  process.exit(1);
}
const chromium = await chromiumOrSkip();
mkdirSync(outDir, { recursive: true });
const ex = join(sourceDir, "examples/gcode");
const { server, url } = await startServer(pkmBinary);
const browser = await launch(chromium);
const errors = [];
try {
  const page = await watchedPage(browser, new URL(url).origin, { width: 1366, height: 768 }, errors, []);
  const shot = (name) => page.screenshot({ path: join(outDir, `web-${name}-1366.png`) });
  await page.goto(url);
  await page.evaluate(() => window.pkmApp.ready);
  await page.waitForTimeout(300);
  await shot("machine");

  await page.click("button[data-view=program]");
  await page.setInputFiles("#open-ngc", [join(ex, "sphere.ngc"), join(ex, "tools.tbl")]);
  await page.waitForFunction(() => window.pkmApp.views.program.toolTable.length > 0);
  await page.click("#run");
  await page.waitForSelector("#program-results .summary b", { timeout: 60000 });
  await page.evaluate(() => window.pkmApp.views.program.sim.seek(60));
  await shot("program");
  await page.check("#program-results .mach-on");
  await page.selectOption("#program-results .mach-stock", "box");
  await page.fill("#program-results .mach-dims", "25,15,-10,75,65,20");
  await page.click("#run");
  await page.waitForSelector("#program-results .machining-summary", { timeout: 60000 });
  await page.evaluate(() => window.pkmApp.views.program.sim.seek(120));
  await page.click("#program-results .mach-zoom");
  await page.waitForTimeout(200);
  await shot("machining");

  await page.click("button[data-view=blocks]");
  await page.click("#blocks-run");
  await page.waitForSelector("#blocks-results .summary b", { timeout: 60000 });
  await page.evaluate(() => window.pkmApp.views.blocks.sim.seek(30));
  await shot("blocks");

  await page.click("button[data-view=campaign]");
  await page.click("#campaign-run");
  await page.waitForFunction(() => window.pkmApp.views.campaign.finished, null, { timeout: 120000 });
  await page.waitForTimeout(500);
  await shot("campaign");
} finally {
  await browser.close();
  server.kill();
}
if (errors.filter((e) => !e.includes("ERR_ABORTED")).length) {
  console.error(errors);
  process.exit(1);
}
console.log(`screenshots in ${outDir}`);
