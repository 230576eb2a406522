// Bundles the browser code of snapfit's pages with esbuild: for each page (run_report:
// report.html of `snapfit run`; chart_page: benchmark and tuning charts; live_page: the
// page of `snapfit serve`) one minified
// script and one style sheet in OUT, which CMake embeds into the library
// (cmake/EmbedWebAssets.cmake). Usage: node build.mjs --out DIR
import { build } from 'esbuild';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const at = process.argv.indexOf('--out');
if (at < 0 || !process.argv[at + 1]) {
  console.error('usage: node build.mjs --out DIR');
  process.exit(2);
}
const outdir = path.resolve(process.argv[at + 1]);

await build({
  absWorkingDir: here,
  entryPoints: { run_report: 'src/run_report.js', chart_page: 'src/chart_page.js', live_page: 'src/live_page.js' },
  outdir,
  bundle: true,
  minify: true,
  format: 'iife',
  target: ['es2020'],
  charset: 'ascii',       // the bundle goes into a C++ raw string literal
  legalComments: 'eof',   // the libraries' licence notices stay with their code
  logLevel: 'warning',
});
