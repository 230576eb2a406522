#!/usr/bin/env bash
# The pages the browser tests open (CTest fixture `browser_pages`):
#   OUT/run/       snapfit run of scenes/default.json (simulated time, m' fixed): report.html
#   OUT/no_loop/   the same scene without its trajectory: report.html with no playback
#   OUT/tune.html  snapfit tune --html: a chart page
# Usage: tests/browser_pages.sh SNAPFIT NODE OUT (from the source tree). The fields, spectra
# and tuning go to OUT/cache, so a run starts cold and leaves the user's cache alone.
set -euo pipefail
snapfit=$1
node=$2
out=$3
rm -rf "$out"
mkdir -p "$out"
export SNAPFIT_CACHE_DIR="$out/cache"
"$snapfit" run scenes/default.json --modes 2048 --simulated-time --out "$out/run"
"$node" -e '
  const fs = require("fs");
  const scene = JSON.parse(fs.readFileSync("scenes/default.json", "utf8"));
  delete scene.trajectory;
  scene.name += " (no trajectory)";
  fs.writeFileSync(process.argv[1], JSON.stringify(scene, null, 2));' "$out/no_loop.json"
"$snapfit" run "$out/no_loop.json" --modes 2048 --out "$out/no_loop"
"$snapfit" tune scenes/default.json --repetitions 20 --budget 20 --html "$out/tune.html"
