// Bundles the pkm serve web application (docs/web.md) with esbuild: src/main.js and its npm
// imports into one app.js, the CSS into app.css, and index.html copied. Nothing is loaded from
// outside the pkm binary at run time.
// Usage: node build.mjs --out DIR
import { build } from "esbuild";
import { copyFileSync, mkdirSync, readdirSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const at = process.argv.indexOf("--out");
if (at < 0 || !process.argv[at + 1]) {
  console.error("usage: node build.mjs --out DIR");
  process.exit(2);
}
const out = process.argv[at + 1];
mkdirSync(out, { recursive: true });
await build({
  entryPoints: { app: join(here, "src/main.js") },
  bundle: true,
  minify: true,
  format: "iife",
  target: "es2020",
  outdir: out,
  loader: { ".css": "css" },
  legalComments: "none",
  logLevel: "warning",
});
copyFileSync(join(here, "src/index.html"), join(out, "index.html"));
// Blockly's icons and cursors, served from /media/ (the workspace's `media` option).
const media = join(here, "node_modules/blockly/media");
mkdirSync(join(out, "media"), { recursive: true });
for (const f of readdirSync(media)) if (!f.endsWith(".mp3")) copyFileSync(join(media, f), join(out, "media", f));
