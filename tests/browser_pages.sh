#!/usr/bin/env bash
# The pages the browser tests open (CTest fixture `browser_pages`):
#   OUT/run/       snapfit run of scenes/default.json (simulated time, m' fixed): report.html
#   OUT/no_loop/   the same scene without its trajectory: report.html with no playback
#   OUT/unjudged/  the same scene without its assembled pose: a run with no verdict
#   OUT/vps/       scenes/peg_hole_clearance_0p5.json with "method": "vps": a run without m'
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
"$node" -e '
  const fs = require("fs");
  const scene = JSON.parse(fs.readFileSync("scenes/default.json", "utf8"));
  delete scene.assembled_pose;
  scene.name += " (no assembled pose)";
  fs.writeFileSync(process.argv[1], JSON.stringify(scene, null, 2));
  const vps = JSON.parse(fs.readFileSync("scenes/peg_hole_clearance_0p5.json", "utf8"));
  vps.method = "vps";
  vps.vps = { voxel_size: 0.5 };
  fs.writeFileSync(process.argv[2], JSON.stringify(vps, null, 2));' "$out/unjudged.json" "$out/vps.json"
"$snapfit" run "$out/unjudged.json" --modes 2048 --simulated-time --out "$out/unjudged"
"$snapfit" run "$out/vps.json" --simulated-time --out "$out/vps"
"$snapfit" tune scenes/default.json --repetitions 20 --budget 20 --html "$out/tune.html"
