#!/usr/bin/env python3
"""How tightly can the two band sums predict the truncation error at a pose?

Reads poses.csv from perf/bench_error_estimate (per pose and m': the true error and the
band sums (m'/4, m'/2] and (m'/2, m']) and prints, per m' and output, the spread
p95 / p50 of error / estimate for three estimators (before any scale):

  rss     the shipped one: root sum of squares of the two bands, per output
  pooled  E and F bands pooled into one variance: F's bands divided by the median
          |F band| / |E band| of that m' count as three more samples of E's scale
  none    a constant (the truth's own spread across the poses)

A fixed scale c covers 95 % of poses when c >= p95 and overestimates the median pose by
c / p50, so coverage >= 95 % with a median overestimate <= 3x needs a spread <= 3.

  python3 perf/error_estimate_spread.py results/bench_error_estimate/poses.csv
"""
import csv
import math
import statistics
import sys


def quantile(values, p):
    v = sorted(values)
    x = p * (len(v) - 1)
    lo = int(math.floor(x))
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (x - lo)


def norm(v):
    return math.sqrt(sum(x * x for x in v))


def main(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    outputs = {"E": ["E"], "F": ["Fx", "Fy", "Fz"], "T": ["Tx", "Ty", "Tz"]}

    def block(r, name, out):
        return [float(r[f"{name}_{c}"]) for c in outputs[out]]

    for m in sorted({int(r["modes"]) for r in rows}):
        at_m = [r for r in rows if int(r["modes"]) == m]
        k = statistics.median(
            norm(block(r, b, "F")) / max(abs(block(r, b, "E")[0]), 1e-300) for r in at_m for b in ("band_a", "band_b"))
        line = [f"m' {m:6d}"]
        for out in ("E", "F", "T"):
            spreads = {}
            for est in ("rss", "pooled", "none"):
                ratios = []
                for r in at_m:
                    truth = norm(block(r, "error", out))
                    if est == "none":
                        e = 1.0
                    elif est == "rss" or out == "T":
                        e = math.hypot(norm(block(r, "band_a", out)), norm(block(r, "band_b", out)))
                    else:
                        s2 = sum(block(r, b, "E")[0] ** 2 + norm(block(r, b, "F")) ** 2 / k**2
                                 for b in ("band_a", "band_b")) / 4
                        e = math.sqrt(s2) * (k if out == "F" else 1.0)
                    if e > 0:
                        ratios.append(truth / e)
                spreads[est] = quantile(ratios, 0.95) / quantile(ratios, 0.5)
            line.append(f"{out}: rss {spreads['rss']:.1f} pooled {spreads['pooled']:.1f} none {spreads['none']:.1f}")
        print("  ".join(line))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: error_estimate_spread.py poses.csv")
    main(sys.argv[1])
