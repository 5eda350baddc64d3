// Builds the playground's site into a folder: node build.mjs MODULE_DIR OUT_DIR, where MODULE_DIR
// holds tracer.js, tracer.wasm and tracer.data (emcmake's build of src/web). The page's script
// is bundled with esbuild (CodeMirror and tracer's grammar in it); the rest is copied as it is.
import { build } from "esbuild";
import { createHash } from "node:crypto";
import { copyFileSync, mkdirSync, readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";

const [moduleDir, outDir] = process.argv.slice(2);
if (!moduleDir || !outDir) {
  console.error("usage: node build.mjs MODULE_DIR OUT_DIR");
  process.exit(2);
}
mkdirSync(outDir, { recursive: true });
await build({
  entryPoints: ["src/main.js"],
  bundle: true,
  minify: true,
  format: "iife",
  target: "es2022",
  outfile: join(outDir, "app.js"),
  logLevel: "warning",
});
for (const name of ["index.html", "style.css", "worker.js"]) copyFileSync(join("src", name), join(outDir, name));
for (const name of ["tracer.js", "tracer.wasm", "tracer.data"]) copyFileSync(join(moduleDir, name), join(outDir, name));
const files = ["./", "index.html", "style.css", "app.js", "worker.js", "tracer.js", "tracer.wasm", "tracer.data"];
const version = createHash("sha256");
for (const name of files.slice(1)) version.update(readFileSync(join(outDir, name)));
const worker = readFileSync("src/sw.js", "utf8");
writeFileSync(
  join(outDir, "sw.js"),
  `const FILES = ${JSON.stringify(files)};\nconst VERSION = "${version.digest("hex").slice(0, 16)}";\n${worker}`,
);
