#!/usr/bin/env bash
# The device bridge's round trip on localhost: `snapfit serve` on the default scene, the
# C++ bridge client (examples/bridge) playing the insertion RUNS times at 997 Hz (a
# device's clock is not the loop's: every phase between them comes up); per run
# the p50 and p99 from sending a state to receiving the first wrench the loop computed
# from it, and their medians over the runs, in OUT/summary.json.
#   perf/bench_bridge.sh [RUNS (3)] [OUT (results/bench_bridge)] [SERVE_ARGS...]  (BUILD=build)
set -euo pipefail
runs=${1:-3} out=${2:-results/bench_bridge} build=${BUILD:-build}
shift $(($# < 2 ? $# : 2))
mkdir -p "$out"
read -r http bridge pid < <(bash tests/serve_session.sh "$build/snapfit" scenes/default.json "$out/serve" "$@")
trap 'kill "$pid" 2>/dev/null' EXIT
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
for _ in $(seq 1 "$runs"); do
  "$build/snapfit_bridge_client" "$bridge" scenes/default.json 997 0.5
  sleep 1.2  # the session releases the client after 1 s of silence
done | tee "$out/runs.jsonl"
python3 - "$out" "$load_before" "$*" "http://127.0.0.1:$http/quit" <<'PY'
import json, statistics as st, sys, urllib.request as u
out, before, args, quit_url = sys.argv[1:]
u.urlopen(u.Request(quit_url, data=b"{}", method="POST"))
runs = [json.loads(l) for l in open(f"{out}/runs.jsonl")]
s = {"runs": runs, "serve_args": args, "load_before": before, "load_after": open("/proc/loadavg").read()[:14],
     **{f"{k}_median": st.median(r[k] for r in runs) for k in ("round_trip_ms_p50", "round_trip_ms_p99")}}
json.dump(s, open(f"{out}/summary.json", "w"), indent=2)
print(f"round trip over {len(runs)} runs: p50 {s['round_trip_ms_p50_median']:.3f} ms, p99 "
      f"{s['round_trip_ms_p99_median']:.3f} ms (medians); load {before} -> {s['load_after']}; {out}/summary.json")
PY
