#!/usr/bin/env bash
# `snapfit serve` driven by the device bridge's example clients, as a device program
# would: the Python client (no build) plays the default scene's insertion at 1 kHz, then,
# once the session has released it (1 s of silence), the C++ client plays it again; each
# must get a wrench back for most of its states and the session must end assembled; it
# is told to quit by a POST with no body at all.
#   tests/serve_bridge.sh SNAPFIT BRIDGE_CLIENT SOURCE_DIR
set -euo pipefail
snapfit=$1 client=$2 source=$3
work=$(mktemp -d)
export SNAPFIT_CACHE_DIR=$work/cache
pid=
cleanup() { [ -n "$pid" ] && kill "$pid" 2>/dev/null; rm -rf "$work"; }
trap cleanup EXIT
read -r http bridge pid < <(bash "$source/tests/serve_session.sh" "$snapfit" "$source/scenes/default.json" \
                              "$work/serve" --modes 2048 --strategy tricubic)
jq_states() { python3 -c 'import json, sys; print(json.loads(sys.argv[1])["states"])' "$1"; }
check_client() {  # name, its JSON line
  python3 - "$1" "$2" <<'PY'
import json, sys
name, r = sys.argv[1], json.loads(sys.argv[2])
assert "refused" not in r, f"{name}: refused: {r}"
assert r["wrenches"] >= 0.5 * r["states"], f"{name}: {r['wrenches']} wrenches for {r['states']} states"
assert r["round_trip_ms_p50"] is not None, f"{name}: no round trip timed"
print(f"{name}: {r['states']} states, {r['wrenches']} wrenches back, round trip p50 {r['round_trip_ms_p50']:.2f} ms")
PY
}
python_out=$(python3 "$source/examples/bridge/snapfit_bridge.py" --port "$bridge" --scene "$source/scenes/default.json")
check_client python "$python_out"
sleep 1.5  # the session releases a client after 1 s of silence
cpp_out=$("$client" "$bridge" "$source/scenes/default.json")
check_client c++ "$cpp_out"
# POST /quit as `curl -X POST URL` sends it: no body, no Content-Length.
python3 - "$http" <<'PY'
import socket, sys
s = socket.create_connection(("127.0.0.1", int(sys.argv[1])))
s.sendall(b"POST /quit HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n")
reply = b""
while chunk := s.recv(4096):
    reply += chunk
head = reply.split(b"\r\n", 1)[0].decode()
assert head.startswith("HTTP/1.1 200"), f"FAIL: POST /quit without a body: {head}"
assert b'"ok":true' in reply, f"FAIL: POST /quit without a body: {reply!r}"
print(f"POST /quit without a body: {head}")
PY
for _ in $(seq 1 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
kill -0 "$pid" 2>/dev/null && { echo "FAIL: snapfit serve did not end after POST /quit"; exit 1; }
pid=
tail -n 2 "$work/serve.log"
sent=$(( $(jq_states "$python_out") + $(jq_states "$cpp_out") ))
grep -q "bridge: $sent states, 0 malformed, 0 refused" "$work/serve.log" || { echo "FAIL: bridge counts (the clients sent $sent states)"; exit 1; }
grep -q ": ASSEMBLED" "$work/serve.log" || { echo "FAIL: the session did not end assembled"; exit 1; }
