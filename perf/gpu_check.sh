#!/usr/bin/env bash
# One GPU check: runs the same measurements on any OpenCL device and writes them, with a
# one-page summary, into one folder, so that figures from different GPUs compare.
#
#   bash perf/gpu_check.sh OUT [--device SPEC] [--build DIR] [--quick] [--timeout S]
#   bash perf/gpu_check.sh OUT --summary-only     # rewrite OUT/summary.md from OUT's files
#
#   OUT            results folder (created; the files of an earlier check there are replaced)
#   --device SPEC  OpenCL device as `snapfit devices` takes it (default: gpu)
#   --build DIR    the build folder (default: build)
#   --quick        small settings for every step (a few minutes on a CPU): the main job at
#                  m' 2048 on simulated time, 6 accuracy poses, 2 m' values for
#                  bench_queries, a handful of test cases
#   --timeout S    stop any one step after S seconds (recorded as TIMEOUT; default: none)
#
# Steps, each one's console output in its own log in OUT (a failing step does not stop the
# others; the exit status is 1 when any failed, 2 for a usage error or a missing binary):
#   devices        snapfit devices (devices.log) and --json (devices.json)
#   devices_check  snapfit devices --check: the self-check kernel, float and double
#   run            snapfit run scenes/default.json --device SPEC --out OUT/run (the main job)
#   accuracy       snapfit accuracy scenes/default.json --device SPEC (JSON in accuracy.json)
#   bench_queries  bench_queries --latency-only: p50/p99 per query and m' (OUT/bench_queries)
#   bench_search   bench_search --quick: snapfit search's maps per second (OUT/bench_search)
#   bench_fft      bench_fft --quick: clFFT, VkFFT and FFTW (skipped when it was not built:
#                  FFTW or VkFFT missing at configure time)
#   tests          the doctest suite (BUILD/tests/snapfit_tests, console report in
#                  tests.log). The tests take the default device (select_device(""): PoCL's
#                  CPU where present), not $SNAPFIT_DEVICE, so when SPEC is not the default
#                  the script makes it so for the suite alone: OCL_ICD_VENDORS narrowed to
#                  the ICD that has it, or POCL_DEVICES for a PoCL device; summary.md names
#                  the device the suite ran on.
# Then OUT/summary.md: date, host, devices, driver, commit, the steps (status, seconds, log)
# and the headline figures read from the outputs ("not found" where a file lacks one). It is
# also printed at the end. Needs bash, coreutils, grep and sed; python3 for the figures
# (without it summary.md says so: rerun --summary-only on OUT where python3 is).
#
# Here (a machine with the build and a GPU that its OpenCL loader lists):
#   bash perf/gpu_check.sh results/gpu_check
#   bash perf/gpu_check.sh /tmp/gpu_check_try --device cpu --quick     # a trial on PoCL
# On a GPU machine without this project's Debian packages (../shared/gpu/README.md): build
# and pack here, then in the copy of the checkout there:
#   bash .ci/setup && bash ../shared/gpu/bundle.sh
#   bash .gpu/run.sh 'bash perf/gpu_check.sh "$OUT/gpu"'
# (run.sh unpacks build/, registers NVIDIA's OpenCL driver alone and starts with an empty
# HOME; where only a few files may come back from such a machine, pack the folder:
#   bash .gpu/run.sh 'bash perf/gpu_check.sh /tmp/gpu; cp /tmp/gpu/summary.md "$OUT/";
#                     tar -C /tmp -czf "$OUT/gpu_check.tar.gz" gpu' )
set -uo pipefail

usage() { sed -n '2,/^set -uo/p' "$0" | sed '$d; s/^# \{0,1\}//'; }
die_usage() { echo "gpu_check.sh: $1" >&2; echo "usage: bash perf/gpu_check.sh OUT [--device SPEC] [--build DIR] [--quick] [--timeout S] (--help for more)" >&2; exit 2; }

out="" device=gpu build=build quick=0 timeout_s=0 summary_only=0
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --device) [ $# -ge 2 ] || die_usage "--device needs a value"; device=$2; shift ;;
    --device=*) device=${1#--device=} ;;
    --build) [ $# -ge 2 ] || die_usage "--build needs a value"; build=$2; shift ;;
    --build=*) build=${1#--build=} ;;
    --quick) quick=1 ;;
    --timeout) [ $# -ge 2 ] || die_usage "--timeout needs a value"; timeout_s=$2; shift ;;
    --timeout=*) timeout_s=${1#--timeout=} ;;
    --summary-only) summary_only=1 ;;
    -*) die_usage "unknown option $1" ;;
    *) [ -z "$out" ] || die_usage "one OUT folder only (got '$out' and '$1')"; out=$1 ;;
  esac
  shift
done
[ -n "$out" ] || die_usage "OUT (the results folder) is missing"
[[ $timeout_s =~ ^[0-9]+$ ]] || die_usage "--timeout takes whole seconds (got '$timeout_s')"

root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out" || { echo "gpu_check.sh: cannot create $out" >&2; exit 2; }
out=$(cd "$out" && pwd)
cd "$root" || exit 2
case "$build" in /*) ;; *) build=$root/$build ;; esac
snapfit=$build/snapfit
tests_bin=$build/tests/snapfit_tests
scene=scenes/default.json
steps_file=$out/steps.tsv
meta_file=$out/meta.tsv
python=${GPU_CHECK_PYTHON:-python3}

# ---------------------------------------------------------------------------------------------
# helpers

# jget KEY LINE: a field of a flat one-line JSON object (strings, numbers, booleans)
jget() {
  local v
  v=$(printf '%s\n' "$2" | sed -n "s/.*\"$1\":\"\([^\"]*\)\".*/\1/p")
  [ -n "$v" ] || v=$(printf '%s\n' "$2" | sed -n "s/.*\"$1\":\([^,}\"]*\).*/\1/p")
  printf '%s' "$v"
}
# device_key LINE: what identifies a device across processes (indices can differ)
device_key() { printf '%s|%s|%s' "$(jget platform "$1")" "$(jget name "$1")" "$(jget driver_version "$1")"; }
# describe LINE: "[i] p:d name (type, platform, driver X)", as snapfit prints it
describe() {
  printf '[%s] %s:%s %s (%s, %s, driver %s)' "$(jget index "$1")" "$(jget platform_index "$1")" \
    "$(jget device_index "$1")" "$(jget name "$1")" "$(jget type "$1")" "$(jget platform "$1")" "$(jget driver_version "$1")"
}
# default_device_under [VAR=VALUE...]: the JSON line of the default device with that environment
default_device_under() { env "$@" timeout 120 "$snapfit" devices --json 2>/dev/null | grep -m1 '"selected":true'; }

seconds_since() {  # START_NS -> seconds with one decimal
  local ns=$(( $(date +%s%N) - $1 ))
  printf '%d.%d' $((ns / 1000000000)) $(((ns / 100000000) % 10))
}

step_no=0
step_total=8
any_failed=0
# record NAME STATUS SECONDS LOG NOTE
record() { printf '%s\t%s\t%s\t%s\t%s\n' "$1" "$2" "$3" "${4#"$out"/}" "$5" >> "$steps_file"; }
meta() { printf '%s\t%s\n' "$1" "$2" >> "$meta_file"; }

# timed NAME LOG STDOUT NOTE CMD...: runs CMD with stderr (and stdout unless STDOUT is a file
# name other than "-") into LOG, records status and seconds
timed() {
  local name=$1 log=$2 stdout=$3 note=$4 start rc secs status
  shift 4
  step_no=$((step_no + 1))
  printf 'gpu_check: [%d/%d] %s:' "$step_no" "$step_total" "$name"; printf ' %q' "$@"; printf '\n'
  { printf '$'; printf ' %q' "$@"; [ "$stdout" = - ] || printf ' > %q' "$stdout"; printf '\n'; } > "$log"
  [ "$stdout" = - ] && stdout=$log
  local pre=()
  [ "$timeout_s" -gt 0 ] && pre=(timeout -k 10 "$timeout_s")
  start=$(date +%s%N)
  if [ "$stdout" = "$log" ]; then "${pre[@]}" "$@" >> "$log" 2>&1; else "${pre[@]}" "$@" > "$stdout" 2>> "$log"; fi
  rc=$?
  secs=$(seconds_since "$start")
  if [ $rc = 0 ]; then status=ok
  elif [ "$timeout_s" -gt 0 ] && { [ $rc = 124 ] || [ $rc = 137 ]; }; then status="TIMEOUT after ${timeout_s} s"; any_failed=1
  elif [ $rc -gt 128 ]; then status="FAILED (signal $((rc - 128)))"; any_failed=1
  else status="FAILED (exit $rc)"; any_failed=1
  fi
  record "$name" "$status" "$secs" "$log" "$note"
  printf '  %s, %s s, log %s\n' "$status" "$secs" "${log#"$out"/}"
  return 0
}
skip() {  # NAME REASON
  step_no=$((step_no + 1))
  printf 'gpu_check: [%d/%d] %s: skipped: %s\n' "$step_no" "$step_total" "$1" "$2"
  record "$1" "skipped: $2" "" "" ""
}

# ---------------------------------------------------------------------------------------------
# summary.md

write_summary_header() {
  local s=$out/summary.md
  local v
  v() { local x; x=$(sed -n "s/^$1\t//p" "$meta_file" 2>/dev/null | head -1); printf '%s' "${x:-not found}"; }
  {
    echo "# snapfit GPU check: $(v device_asked) ($(v mode))"
    echo
    echo "- date (UTC): $(v date)"
    echo "- host: $(v host)"
    echo "- GPU (nvidia-smi): $(v nvidia_smi)"
    echo "- device: $(v device)"
    echo "- driver: $(v driver)"
    echo "- commit: $(v commit)"
    echo "- build: $(v build)"
    echo
    echo "\`snapfit devices\`:"
    echo
    echo '```text'
    if grep -qE '^[* ] \[[0-9]+\]' "$out/devices.log" 2>/dev/null; then
      grep -E '^[* ] \[[0-9]+\]|^      OpenCL' "$out/devices.log" | head -16
    else
      echo "not found"
    fi
    echo '```'
    echo
    echo "| step | status | seconds | log |"
    echo "|---|---|---|---|"
    while IFS=$'\t' read -r name status secs log note; do
      echo "| $name | $status${note:+ ($note)} | ${secs:--} | ${log:--} |"
    done < "$steps_file"
    echo
  } > "$s"
}

write_figures_python() {
  "$python" - "$out" <<'PY'
import json, os, re, sys

out = sys.argv[1]
meta = {}
try:
    for line in open(os.path.join(out, "meta.tsv")):
        k, _, v = line.rstrip("\n").partition("\t")
        meta.setdefault(k, v)
except OSError:
    pass
quick = meta.get("mode", "").startswith("quick")
NF = "not found"
lines = []
w = lines.append


def load(rel):
    try:
        with open(os.path.join(out, rel)) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def text(rel):
    try:
        with open(os.path.join(out, rel), errors="replace") as f:
            return f.read()
    except OSError:
        return ""


steps = [line.split("\t") for line in text("steps.tsv").splitlines()]


def g(d, *keys):
    for k in keys:
        if isinstance(d, dict) and k in d:
            d = d[k]
        else:
            return None
    return d


def num(x, digits=3):
    if x is None or isinstance(x, bool):
        return NF
    if isinstance(x, int):
        return "{:,}".format(x)
    if isinstance(x, float):
        if x != 0 and (abs(x) >= 10 ** digits):
            return "{:,.0f}".format(x)
        return "{:.{}g}".format(x, digits)
    return str(x)


def pct(x):
    if not isinstance(x, (int, float)) or isinstance(x, bool):
        return NF
    p = 100.0 * x
    return "{:.0f} %".format(p) if abs(p) >= 100 else "{:.2g} %".format(p)


def ms(x_s):
    return NF if not isinstance(x_s, (int, float)) else num(1e3 * x_s)


# ---- main job
w("## Main job (run/summary.json)")
w("")
s = load("run/summary.json")
if s is None:
    w("run/summary.json " + NF + ".")
else:
    hl = g(s, "haptic_loop") or {}
    tuned = g(s, "tuning", "chosen_modes")
    extra = ""
    if quick:
        extra = " (--modes 2048 --simulated-time: m' fixed, not tuned; frame times have no timing meaning)"
    w("- device: {}; loop device: {}; self-check: {}".format(
        g(s, "device") or NF, g(s, "loop_device") or NF,
        {True: "passed", False: "FAILED"}.get(g(s, "device_check_passed"), NF)))
    w("- tuned m': {}{}".format(num(tuned), extra))
    qs = g(s, "query_strategy")
    if isinstance(qs, dict) and qs.get("name"):
        w("- query strategy: {}{}".format(qs["name"], "; chosen by: " + str(qs["chosen_by"]) if qs.get("chosen_by") else ""))
    w("- frame: p50 {} ms, p99 {} ms, max {} ms; {} frames at {} Hz".format(
        num(g(hl, "frame_ms", "p50")), num(g(hl, "frame_ms", "p99")), num(g(hl, "frame_ms", "max")),
        num(g(hl, "frames")), num(g(hl, "measured_rate_hz"), 5)))
    rate = g(hl, "miss_rate")
    w("- misses: {}{}".format(num(g(hl, "misses")), " ({})".format(pct(rate)) if isinstance(rate, (int, float)) else ""))
    verdict = {True: "ASSEMBLED", False: "NOT assembled"}.get(g(hl, "assembled"), NF)
    units = g(s, "units") or ""
    w("- final pose: {}, {} {} and {} deg from the fit (tolerance {} {}, {} deg)".format(
        verdict, num(g(hl, "final_error", "position")), units, num(g(hl, "final_error", "angle_deg")),
        num(g(hl, "tolerance", "position")), units, num(g(hl, "tolerance", "angle_deg"))))
    w("- the job took {} s".format(num(g(s, "seconds"))))
w("")

# ---- accuracy
w("## Accuracy (accuracy.json)")
w("")
a = load("accuracy.json")
if a is None:
    w("accuracy.json " + NF + ".")
else:
    w("Device {}, budget {} ms, {} poses, reference: {} modes. Chosen: {}; lowest error within the budget: {}.".format(
        g(a, "device") or NF, num(g(a, "budget_ms")), num(g(a, "poses")), num(g(a, "reference", "modes")),
        g(a, "strategy") or NF, g(a, "lowest_error_within_budget") or NF))
    w("")
    w("| strategy | m' | frame p50 ms | frame p99 ms | fits | E error | F error | T error |")
    w("|---|---|---|---|---|---|---|---|")
    for st in g(a, "strategies") or []:
        w("| {} | {} | {} | {} | {} | {} | {} | {} |".format(
            g(st, "strategy") or NF, num(g(st, "modes")), num(g(st, "frame_ms_p50")), num(g(st, "frame_ms_p99")),
            {True: "yes", False: "no"}.get(g(st, "fits_budget"), NF),
            pct(g(st, "energy_error")), pct(g(st, "force_error")), pct(g(st, "torque_error"))))
    if not g(a, "strategies"):
        w("| " + NF + " | | | | | | | |")
w("")

# ---- bench_queries
w("## bench_queries: latency per query, p50 / p99 in us (bench_queries/queries.json)")
w("")
q = load("bench_queries/queries.json")
rows = [r for r in (g(q, "latency") or []) if g(r, "source") == "measured"]
if not rows:
    w("bench_queries/queries.json " + ("has no measured latency point." if q else NF + "."))
else:
    w("Device {}, {} timed queries per point.".format(g(q, "device", "name") or NF, num(rows[0].get("repeats"))))
    w("")
    modes = sorted({r.get("modes_used", r.get("modes")) for r in rows})
    variants = []
    for r in rows:
        if r.get("variant") not in [v[0] for v in variants]:
            variants.append((r.get("variant"), r.get("label") or r.get("variant")))
    w("| variant | " + " | ".join("m' " + num(m) for m in modes) + " |")
    w("|---|" + "---|" * len(modes))
    for key, label in variants:
        cells = []
        for m in modes:
            r = next((r for r in rows if r.get("variant") == key and r.get("modes_used", r.get("modes")) == m), None)
            cells.append("{} / {}".format(num(r.get("p50_us")), num(r.get("p99_us"))) if r else "-")
        w("| {} | {} |".format(label, " | ".join(cells)))
w("")

# ---- bench_search
w("## bench_search --quick: rotations per second (bench_search/search.json)")
w("")
b = load("bench_search/search.json")
srows = g(b, "rows") or []
if not srows:
    w("bench_search/search.json " + (NF + "." if b is None else "has no rows."))
else:
    picks = {n: (f, int(b or 1)) for n, f, b in
             re.findall(r"^(\d+)\^3 \w+: choose_map_fft picks (\w+)(?: x(\d+))?", text("bench_search.log"), re.M)}
    w("Device {}. Per rotation, ms: product, inverse FFT, minima kernel (device), read-back (the map, or the "
      "list of minima), host map, minima on the host (map_minima, or the list's thinning); not timed for "
      "batches.".format(g(b, "device") or NF))
    w("")
    w("| size | interpolation | FFT | minima on | rotations/s (median) | whole scan | per rotation, ms |")
    w("|---|---|---|---|---|---|---|")
    for r in srows:
        n = r.get("n")
        fft = str(r.get("fft"))
        batch = int(r.get("batch", 1) or 1)
        if picks.get(str(n)) == (fft, batch):
            fft += " (picked)"
        if batch > 1:
            fft += ", batches of {}".format(batch)
        stages = "not timed (batched)" if batch > 1 else "{} / {} / {} / {} / {} / {}".format(
            ms(r.get("product_s")), ms(r.get("inverse_fft_s")), ms(r.get("reduce_s", 0)), ms(r.get("read_s")),
            ms(r.get("host_map_s")), ms(r.get("minima_s")))
        w("| {}^3 | {} | {} | {} | {} | {} | {} |".format(
            n, r.get("interpolation", NF), fft, r.get("minima_on", "host"), num(r.get("rotations_per_s_median"), 4),
            num(r.get("rotations_per_s_scan"), 4), stages))
w("")

# ---- bench_fft
w("## bench_fft --quick (bench_fft/fft.json)")
w("")
f = load("bench_fft/fft.json")
if f is None:
    st = next((p[1] for p in steps if len(p) >= 2 and p[0] == "bench_fft"), "")
    w("bench_fft/fft.json " + NF + (" (" + st + ")" if st.startswith("skipped") else "") + ".")
else:
    tr = g(f, "transforms") or []
    libs = []
    for r in tr:
        if r.get("library") not in libs:
            libs.append(r.get("library"))
    w("Device {}. 3D complex transforms, p50 ms:".format(g(f, "device", "name") or NF))
    w("")
    w("| size | direction | " + " | ".join(str(l) for l in libs) + " |")
    w("|---|---|" + "---|" * len(libs))
    seen = []
    for r in tr:
        k = (tuple(r.get("dims") or []), r.get("direction"))
        if k in seen:
            continue
        seen.append(k)
        cells = []
        for l in libs:
            x = next((x for x in tr if (tuple(x.get("dims") or []), x.get("direction")) == k and x.get("library") == l), None)
            cells.append(num(x.get("p50_ms")) if x else "-")
        w("| {} | {} | {} |".format("x".join(str(d) for d in k[0]), k[1], " | ".join(cells)))
    mp = g(f, "maps") or []
    if mp:
        w("")
        w("Full maps (product + inverse FFT), rotations/s: " + "; ".join(
            "{} {} {}".format("x".join(str(d) for d in (r.get("dims") or [])), r.get("path"), num(r.get("rotations_per_s"), 4))
            for r in mp) + ".")
    w("")
    w("Verdict: " + (g(f, "verdict") or NF))
w("")

# ---- tests
w("## Tests (tests.log)")
w("")
log = text("tests.log")
if not log:
    w("tests.log " + NF + ".")
else:
    dev = re.search(r"MESSAGE: default device: (.*)", log)
    w("- device the suite ran on: " + (dev.group(1).strip() if dev else NF + " (the device enumeration case did not run)"))
    c = re.search(r"^\[doctest\] test cases:\s*(\d+) \|\s*(\d+) passed \|\s*(\d+) failed \|\s*(\d+) skipped", log, re.M)
    if c:
        w("- test cases: {} passed, {} failed (of {} run; {} not selected or skipped)".format(c.group(2), c.group(3), c.group(1), c.group(4)))
    else:
        w("- test cases passed / failed: " + NF + " (no doctest summary: the run ended early)")
    failed, first = [], {}
    cur = None
    lines_ = log.splitlines()
    for i, line in enumerate(lines_):
        m = re.match(r"^TEST CASE:\s+(.*)$", line)
        if m:
            cur = m.group(1).strip()
            continue
        m = re.search(r":\d+: (FATAL ERROR|ERROR): (.*)$", line)
        if m and cur:
            if cur not in failed:
                failed.append(cur)
                why = m.group(2).strip()
                for nxt in lines_[i + 1:i + 4]:
                    if nxt.strip().startswith("logged:"):
                        why += " " + nxt.strip()
                        break
                first[cur] = why if len(why) <= 160 else why[:157] + "..."
    if c and not failed and c.group(3) != "0":
        w("- failed test cases: " + NF + " (names not in the log)")
    elif failed:
        w("- failed test cases:")
        for n in failed:
            w("  - {}: {}".format(n, first.get(n, "")))
    elif not c:
        last = [l for l in lines_ if l.startswith("TEST CASE:")]
        w("- the last test case started: " + (last[-1][10:].strip() if last else NF))
w("")

# ---- failed steps: the end of their logs
tails = []
for parts in steps:
    if len(parts) >= 4 and parts[0] != "tests" and (parts[1].startswith("FAILED") or parts[1].startswith("TIMEOUT")):
        body = [l for l in text(parts[3]).splitlines() if l.strip()][-4:]
        tails.append((parts[0], parts[3], body))
if tails:
    w("## The end of each failed step's log")
    w("")
    for name, logf, body in tails:
        w("{} ({}):".format(name, logf))
        w("```text")
        for l in body:
            w(l if len(l) <= 200 else l[:197] + "...")
        w("```")
    w("")

with open(os.path.join(out, "summary.md"), "a") as fh:
    fh.write("\n".join(lines) + "\n")
PY
}

write_summary() {
  write_summary_header
  local why="no $python on this machine"
  if command -v "$python" > /dev/null 2>&1; then
    cp "$out/summary.md" "$out/.summary_head.md"
    if write_figures_python 2> "$out/.summary_python.err"; then why=""; else
      cp "$out/.summary_head.md" "$out/summary.md"
      why="$python failed on the outputs$(tail -1 "$out/.summary_python.err" | sed 's/^./: &/')"
      echo "gpu_check: the python3 summary failed ($why)" >&2
    fi
    rm -f "$out/.summary_head.md" "$out/.summary_python.err"
  fi
  # The figures need python3; the logs stay in OUT for a rerun where it is.
  [ -z "$why" ] || echo "No figures ($why): run \`bash perf/gpu_check.sh OUT --summary-only\` where python3 is." >> "$out/summary.md"
}

if [ $summary_only = 1 ]; then
  [ -f "$steps_file" ] || { echo "gpu_check.sh: $steps_file is missing: no check ran in $out" >&2; exit 2; }
  write_summary
  cat "$out/summary.md"
  exit 0
fi

# ---------------------------------------------------------------------------------------------
# binaries

missing=0
for b in "$snapfit" "$build/perf/bench_queries" "$build/perf/bench_search" "$tests_bin"; do
  [ -x "$b" ] && continue
  t=$(basename "$b") extra="" missing=1
  [[ $t == bench_* ]] && extra=" in a build configured with -DSNAPFIT_BUILD_BENCHMARKS=ON"
  echo "gpu_check.sh: ${b#"$root"/} is missing: build it with 'cmake --build ${build#"$root"/} --target $t'$extra, or from scratch with 'bash .ci/setup'" >&2
done
if [ $missing = 1 ]; then
  echo "gpu_check.sh: (a GPU machine without this project's Debian packages gets the build from a Debian machine: 'bash ../shared/gpu/bundle.sh' there, 'bash .gpu/run.sh ...' here; ../shared/gpu/README.md)" >&2
  exit 2
fi

# ---------------------------------------------------------------------------------------------
# the steps

rm -rf "$out/run" "$out/bench_queries" "$out/bench_search" "$out/bench_fft"
rm -f "$out"/{devices,devices_check,run,accuracy,bench_queries,bench_search,bench_fft,tests}.log \
  "$out/devices.json" "$out/accuracy.json" "$out/summary.md" "$steps_file" "$meta_file"
: > "$steps_file"
: > "$meta_file"

commit=unknown
if command -v git > /dev/null 2>&1 && c=$(git -C "$root" rev-parse --short HEAD 2> /dev/null); then
  commit=$c
  git -C "$root" diff --quiet HEAD -- 2> /dev/null || commit="$c (with uncommitted changes)"
fi
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2> /dev/null | head -1)
gpu="not found"
if command -v nvidia-smi > /dev/null 2>&1; then
  gpu=$(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2> /dev/null | head -4 | paste -sd ';' -)
  [ -n "$gpu" ] || gpu="not found (nvidia-smi printed nothing)"
fi
meta date "$(date -u '+%Y-%m-%d %H:%M:%S UTC')"
meta host "$(uname -n), ${cpu:-CPU not found}, $(nproc) cores, $(uname -sr)"
meta nvidia_smi "$gpu"
meta commit "$commit"
meta build "${build#"$root"/}"
meta device_asked "--device $device"
if [ $quick = 1 ]; then meta mode "quick"; else meta mode "full"; fi
echo "gpu_check: into $out, --device $device, $([ $quick = 1 ] && echo quick || echo full), build ${build#"$root"/}, commit $commit"

# 1. devices
timed devices "$out/devices.log" - "" "$snapfit" devices
timeout 120 "$snapfit" devices --json > "$out/devices.json" 2>> "$out/devices.log"
target=$(default_device_under "SNAPFIT_DEVICE=$device" || true)  # the device SPEC picks, as the benchmarks pick it
if [ -n "$target" ]; then
  meta device "--device $device is $(describe "$target")"
  meta driver "$(jget driver_version "$target"), $(jget device_version "$target")"
else
  meta device "--device $device matches no device that \`snapfit devices\` lists"
fi
timed devices_check "$out/devices_check.log" - "" "$snapfit" devices --check

# 2. the main job
run_args=(run "$scene" --device "$device" --out "$out/run")
[ $quick = 1 ] && run_args+=(--modes 2048 --simulated-time)
timed run "$out/run.log" - "" "$snapfit" "${run_args[@]}"

# 3. accuracy
acc_args=(accuracy "$scene" --device "$device")
[ $quick = 1 ] && acc_args+=(--poses 6 --repetitions 100)
timed accuracy "$out/accuracy.log" "$out/accuracy.json" "" "$snapfit" "${acc_args[@]}"

# 4-6. benchmarks
if [ $quick = 1 ]; then
  bq_args=(--quick --latency-only --modes "4096,32768")
else
  bq_args=(--latency-only --modes "1024,4096,32768,262144,1048576,2744000")  # 2744000: every mode of the default scene
fi
timed bench_queries "$out/bench_queries.log" - "" "$build/perf/bench_queries" --device "$device" "${bq_args[@]}" --out "$out/bench_queries"
timed bench_search "$out/bench_search.log" - "" "$build/perf/bench_search" --quick --device "$device" --out "$out/bench_search"
if [ -x "$build/perf/bench_fft" ]; then
  timed bench_fft "$out/bench_fft.log" - "" "$build/perf/bench_fft" --quick --device "$device" --out "$out/bench_fft"
elif [ -f "$build/perf/built_benchmarks.txt" ] && ! grep -qx bench_fft "$build/perf/built_benchmarks.txt"; then
  skip bench_fft "not built: FFTW or VkFFT was missing when the build was configured (perf/CMakeLists.txt)"
else
  skip bench_fft "${build#"$root"/}/perf/bench_fft is not there (not built for want of FFTW or VkFFT, or not carried)"
fi

# 7. the test suite, on the device SPEC picks
test_env=() test_note=""
tmp_vendors=""
trap '[ -z "$tmp_vendors" ] || rm -rf "$tmp_vendors"' EXIT
if [ -n "$target" ]; then
  want=$(device_key "$target")
  dflt=$(default_device_under)
  if [ "$(device_key "$dflt")" != "$want" ]; then
    found=0
    vendors=${OCL_ICD_VENDORS:-/etc/OpenCL/vendors}
    pocl_env=()
    if [[ $(jget platform "$target") == *"Portable Computing Language"* ]]; then
      pocl_env=("POCL_DEVICES=$(jget name "$target" | sed 's/-.*//')")
    fi
    candidates=()
    [ -d "$vendors" ] && for icd in "$vendors"/*.icd; do [ -f "$icd" ] && candidates+=("$icd"); done
    tmp_vendors=$(mktemp -d)
    try_env() {  # NOTE VAR=VALUE...: keep the environment when its default device is the target
      local note=$1 d
      shift
      d=$(default_device_under "$@")
      if [ -n "$d" ] && [ "$(device_key "$d")" = "$want" ]; then test_env=("$@") test_note=$note found=1; fi
    }
    if [ ${#pocl_env[@]} -gt 0 ]; then try_env "${pocl_env[*]}" "${pocl_env[@]}"; fi
    for icd in "${candidates[@]}"; do
      [ $found = 1 ] && break
      dir=$tmp_vendors/$(basename "$icd" .icd)
      mkdir -p "$dir" && cp "$icd" "$dir/"
      try_env "OCL_ICD_VENDORS: $(basename "$icd") alone" "OCL_ICD_VENDORS=$dir"
      if [ $found = 0 ] && [ ${#pocl_env[@]} -gt 0 ]; then
        try_env "OCL_ICD_VENDORS: $(basename "$icd") alone, ${pocl_env[*]}" "OCL_ICD_VENDORS=$dir" "${pocl_env[@]}"
      fi
    done
    if [ $found = 0 ]; then
      test_note="on the default device $(describe "$dflt"), not --device $device's: no OpenCL vendor file or PoCL setting makes that device the default"
    fi
  fi
fi
[ -n "$target" ] || test_note="--device $device matches no device: on the default device"
test_args=(-nc -d)
if [ $quick = 1 ]; then
  # a few cases that exercise the device: enumeration and self-check, launch shapes,
  # float accumulation, batches against single queries
  test_args+=("-tc=device enumeration*,device self-check*,pose query: results do not depend on the launch shape*,pose query: query_batch equals a loop of query,stability accumulation*,reference query: the device kernel*")
fi
# in build/tests, as ctest runs them (a bash that cds: env -C needs coreutils 8.28)
# shellcheck disable=SC2016
timed tests "$out/tests.log" - "$test_note" bash -c 'cd "$1" && shift && exec env "$@"' gpu_check "$build/tests" \
  "${test_env[@]}" "$tests_bin" "${test_args[@]}"

# ---------------------------------------------------------------------------------------------
write_summary
echo "gpu_check: wrote $out/summary.md"
echo
cat "$out/summary.md"
exit $any_failed
