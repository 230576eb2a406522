#!/usr/bin/env bash
# `mpirun -np N snapfit search` on loopback: the same poses on 1, 2 and 4 ranks, and a
# rank whose device cannot be opened ends the job with a message naming it (no hang).
#   search_ranks.sh SNAPFIT MPIRUN SOURCE_DIR
# The scene: scenes/peg_hole_clearance_0p5.json at twice its grid spacing (small maps).
set -euo pipefail
snapfit=$1 mpirun=$2 source=$3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export SNAPFIT_CACHE_DIR=$work/cache
sed 's/"spacing": 0.6/"spacing": 1.2/' "$source/scenes/peg_hole_clearance_0p5.json" >"$work/scene.json"
grep -q '"spacing": 1.2' "$work/scene.json" || { echo "FAIL: the scene's spacing was not found"; exit 1; }
run() {  # ranks, extra arguments...
  local n=$1
  shift
  timeout 240 "$mpirun" --oversubscribe --mca btl self,vader -np "$n" "$snapfit" search "$work/scene.json" \
    --rotations 16 --top 4 --refine-queries 10 "$@"
}
for n in 1 2 4; do
  run "$n" >"$work/out$n.txt" 2>"$work/err$n.txt" || { echo "FAIL: $n ranks"; cat "$work/err$n.txt"; exit 1; }
  grep '^{' "$work/out$n.txt" >"$work/poses$n.jsonl"
  grep -q "rank $((n - 1)): " "$work/out$n.txt" || { echo "FAIL: no rotations/s of rank $((n - 1))"; exit 1; }
done
[ "$(wc -l <"$work/poses1.jsonl")" -eq 4 ] || { echo "FAIL: expected 4 poses"; cat "$work/out1.txt"; exit 1; }
for n in 2 4; do
  cmp -s "$work/poses1.jsonl" "$work/poses$n.jsonl" || {
    echo "FAIL: $n ranks differ from 1"
    diff "$work/poses1.jsonl" "$work/poses$n.jsonl"
    exit 1
  }
done
echo "1, 2 and 4 ranks: the same $(wc -l <"$work/poses1.jsonl") poses"
# Rank 1 on a device that does not exist: every rank ends, rank 0 names rank 1.
set +e
start=$SECONDS
run 2 --device ';no-such-device' >"$work/fail.txt" 2>&1
status=$?
set -e
[ "$status" -ne 0 ] && [ "$status" -ne 124 ] || { echo "FAIL: status $status"; cat "$work/fail.txt"; exit 1; }
grep -q "rank 1 of 2 failed: .*no-such-device" "$work/fail.txt" || { echo "FAIL: no message naming rank 1"; cat "$work/fail.txt"; exit 1; }
echo "a failing rank 1 ended the job in $((SECONDS - start)) s: $(grep -m1 'rank 1 of 2' "$work/fail.txt")"
