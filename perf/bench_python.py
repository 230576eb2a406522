"""What the Python layer costs: 10,000 poses through QueryEngine.query from Python against
the same batch timed in C++ around query_batch alone, side by side in one run (alternating,
median of the repeats).

    PYTHONPATH=build/python /usr/bin/python3 perf/bench_python.py [--repeats 9] [--modes 4096]
"""
import argparse
import statistics
import time

import numpy as np

import snapfit


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="scenes/default.json")
    parser.add_argument("--poses", type=int, default=10000)
    parser.add_argument("--modes", type=int, default=4096)
    parser.add_argument("--repeats", type=int, default=9)
    args = parser.parse_args()

    engine = snapfit.Assembly(snapfit.load_scene(args.scene)).query_engine()
    engine.modes = args.modes
    rng = np.random.default_rng(7)
    n = args.poses
    axis = rng.normal(size=(n, 3))
    axis /= np.linalg.norm(axis, axis=1)[:, None]
    half = np.radians(rng.uniform(0, 3, n)) / 2
    poses = np.column_stack([rng.uniform(-0.5, 0.5, (n, 2)), rng.uniform(0, 10, n), np.cos(half),
                             axis * np.sin(half)[:, None]])
    engine.query(poses[:100])  # warm-up: kernels built, buffers sized

    python_s, cpp_s = [], []
    for _ in range(args.repeats):
        start = time.perf_counter()
        engine.query(poses)
        python_s.append(time.perf_counter() - start)
        cpp_s.append(engine._time_batch(poses, 1)[0])
    py_med, cpp_med = statistics.median(python_s), statistics.median(cpp_s)
    print(f"{n} poses, m' {engine.modes}, {engine.variant}, {args.repeats} repeats each, alternating")
    print(f"  from Python (query):          median {1e3 * py_med:9.2f} ms  ({n / py_med:,.0f} poses/s)")
    print(f"  in C++ (query_batch alone):   median {1e3 * cpp_med:9.2f} ms  ({n / cpp_med:,.0f} poses/s)")
    print(f"  Python over C++: {100 * (py_med / cpp_med - 1):+.2f} % (goal within 5 %)")


if __name__ == "__main__":
    main()
