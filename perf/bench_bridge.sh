#!/usr/bin/env bash
# The device bridge's round trip on localhost: `snapfit serve` on the default scene, the
# C++ bridge client (examples/bridge) playing the insertion at 1 kHz, RUNS times in a
# row; for each run the p50 and p99 of the time from sending a state to receiving the
# first wrench the loop computed from it, and their medians over the runs.
#   perf/bench_bridge.sh [--build DIR] [--runs N] [--out DIR] [-- SERVE_ARGS...]
set -euo pipefail
build=build runs=3 out=results/bench_bridge
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build=$2; shift ;;
    --runs) runs=$2; shift ;;
    --out) out=$2; shift ;;
    --) shift; break ;;
    -h|--help) sed -n '2,6p' "$0"; exit 0 ;;
    *) echo "bench_bridge.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
mkdir -p "$out"
read -r http bridge pid < <(bash tests/serve_session.sh "$build/snapfit" scenes/default.json "$out/serve" "$@")
trap 'kill "$pid" 2>/dev/null' EXIT
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
: >"$out/runs.jsonl"
for r in $(seq 1 "$runs"); do
  "$build/snapfit_bridge_client" "$bridge" scenes/default.json 1000 0.5 | tee -a "$out/runs.jsonl"
  sleep 1.2  # the session releases the client after 1 s of silence
done
python3 -c 'import urllib.request as u, sys; u.urlopen(u.Request(sys.argv[1], data=b"{}", method="POST"))' \
  "http://127.0.0.1:$http/quit"
python3 - "$out" "$load_before" "$(cut -d' ' -f1-3 /proc/loadavg)" "$*" <<'PY'
import json, statistics, sys
out, before, after, args = sys.argv[1:]
runs = [json.loads(l) for l in open(f"{out}/runs.jsonl")]
summary = {"runs": runs, "serve_args": args, "load_before": before, "load_after": after,
           "round_trip_ms_p50_median": statistics.median(r["round_trip_ms_p50"] for r in runs),
           "round_trip_ms_p99_median": statistics.median(r["round_trip_ms_p99"] for r in runs),
           "wrenches_per_state_median": statistics.median(r["wrenches"] / r["states"] for r in runs)}
json.dump(summary, open(f"{out}/summary.json", "w"), indent=2)
print(f"round trip over {len(runs)} runs: p50 {summary['round_trip_ms_p50_median']:.3f} ms, "
      f"p99 {summary['round_trip_ms_p99_median']:.3f} ms (medians); load {before} -> {after}; {out}/summary.json")
PY
