#!/usr/bin/env bash
# Runs every benchmark in perf/ into one results folder, with the machine, the load
# average and the time each took, so the numbers in docs/performance.md can be reproduced:
#
#   perf/run_benchmarks.sh [--quick] [--out DIR] [--build DIR] [--only NAME[,NAME...]]
#
# Full mode is for a quiet machine (about 20 minutes on 2 cores); --quick runs each
# benchmark's small mode (CI runs it once to prove everything runs; timings are not
# checked). Each benchmark writes CSV, JSON and a self-contained charts.html into
# DIR/<name>/ and its console output into DIR/<name>.log; with chromium and
# report/web/node_modules present, each charts.html is also shot as charts.png (headless
# chromium). DIR/index.md lists what ran, how long it took and the load average before
# and after.
set -euo pipefail

quick=0
out=results/bench
build=build
only=""
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --out) out="$2"; shift ;;
    --out=*) out="${1#--out=}" ;;
    --build) build="$2"; shift ;;
    --build=*) build="${1#--build=}" ;;
    --only) only="$2"; shift ;;
    --only=*) only="${1#--only=}" ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "run_benchmarks.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done

benches=(bench_descriptors bench_queries bench_haptic_loop bench_fft bench_search bench_peers bench_accuracy bench_error_estimate bench_mode_selection bench_mesh_import bench_assembly bench_spheres bench_collision bench_ndft_crossover bench_contact bench_vouched_wrench bench_mode_step bench_resting_pose bench_real_cad)
mkdir -p "$out"
index="$out/index.md"
{
  echo "# snapfit benchmarks ($([ $quick = 1 ] && echo quick || echo full))"
  echo
  echo "- date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "- machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(free -g | awk '/Mem:/ {print $2}') GiB"
  echo "- commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo
  echo "| benchmark | status | seconds | load before | load after | output |"
  echo "|---|---|---|---|---|---|"
} > "$index"

# Benchmarks whose peer library was missing at configure time are not built (CMake says
# so); they are listed as skipped. Any other missing one is an error.
built_list="$build/perf/built_benchmarks.txt"
if [ ! -f "$built_list" ]; then
  echo "run_benchmarks.sh: $built_list is missing: configure with -DSNAPFIT_BUILD_BENCHMARKS=ON and build" >&2
  exit 2
fi
failed=0
ran=()
for b in "${benches[@]}"; do
  if [ -n "$only" ] && [[ ",$only," != *",$b,"* ]]; then continue; fi
  exe="$build/perf/$b"
  if ! grep -qx "$b" "$built_list"; then
    echo "| $b | skipped: not built (a peer library was missing at configure time) | | | | |" >> "$index"
    echo "run_benchmarks.sh: $b skipped: not built (see the configure output for the missing peer)" >&2
    continue
  fi
  if [ ! -x "$exe" ]; then
    echo "| $b | not built | | | | |" >> "$index"
    echo "run_benchmarks.sh: $exe is missing (build the project first)" >&2
    failed=1
    continue
  fi
  args=(--out "$out/$b")
  [ $quick = 1 ] && args+=(--quick)
  load_before=$(cut -d' ' -f1-3 /proc/loadavg)
  echo "== $b ${args[*]}"
  start=$(date +%s%N)
  if "$exe" "${args[@]}" > >(tee "$out/$b.log") 2>&1; then status=ok; else status="FAILED ($?)"; failed=1; fi
  ran+=("$b")
  seconds=$(awk -v a="$start" -v b="$(date +%s%N)" 'BEGIN { printf "%.1f", (b - a) / 1e9 }')
  load_after=$(cut -d' ' -f1-3 /proc/loadavg)
  printf '| %s | %s | %s | %s | %s | [%s/](%s/) |\n' "$b" "$status" "$seconds" "$load_before" "$load_after" "$b" "$b" >> "$index"
done
# Pictures of the chart pages, for docs: one chromium for all of them.
pages=()
for b in "${ran[@]}"; do
  [ -f "$out/$b/charts.html" ] && pages+=("$out/$b/charts.html" "$out/$b/charts.png")
done
web="$(dirname "$0")/../report/web"
if ((${#pages[@]})) && [ -x "${SNAPFIT_CHROMIUM:-/usr/bin/chromium}" ] && [ -d "$web/node_modules" ]; then
  if node "$web/screenshot.mjs" "${pages[@]}"; then echo "charts.png: one per charts.html"; else
    echo "run_benchmarks.sh: the screenshots of the chart pages failed" >&2; failed=1; fi
else
  echo "run_benchmarks.sh: no charts.png (needs chromium and report/web/node_modules)" >&2
fi
echo "wrote $index"
exit $failed
