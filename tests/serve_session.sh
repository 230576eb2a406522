#!/usr/bin/env bash
# Starts `snapfit serve` on free ports with the given extra arguments and waits until it
# is live; prints "HTTP_PORT BRIDGE_PORT PID" (its output goes to OUT.log). For the tests
# that drive a live session from outside (tests/serve_bridge.sh, the live page's browser
# test).   tests/serve_session.sh SNAPFIT SCENE OUT [ARGS...]
set -euo pipefail
snapfit=$1 scene=$2 out=$3
shift 3
"$snapfit" serve "$scene" --port 0 "$@" >"$out.log" 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  if line=$(grep -m1 "live: the page at" "$out.log"); then
    http=$(sed -E 's/.*127\.0\.0\.1:([0-9]+)\/.*/\1/' <<<"$line")
    bridge=$(sed -E 's/.*UDP 127\.0\.0\.1:([0-9]+).*/\1/' <<<"$line")
    echo "$http $bridge $pid"
    exit 0
  fi
  kill -0 "$pid" 2>/dev/null || { echo "serve_session: snapfit serve ended before it was live:" >&2; cat "$out.log" >&2; exit 1; }
  sleep 0.5
done
kill "$pid"
echo "serve_session: snapfit serve was not live after 300 s" >&2
exit 1
