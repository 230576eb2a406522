"""A parameter sweep a researcher would start from: the error of E, F and T against m' on
poses along the default scene's trajectory, against the largest m' as the reference.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/modes_sweep.py

Prints one line per m': relative RMS error of energy, force and torque over the poses.
"""
import numpy as np

import snapfit


def sweep(scene_file="scenes/default.json", modes=(512, 2048, 8192, 32768), reference=131072):
    engine = snapfit.Assembly(snapfit.load_scene(scene_file)).query_engine()
    # Poses down the hole with a small, varying tilt about x (x, y, z, qw, qx, qy, qz).
    z = np.linspace(10.0, 0.0, 40)
    tilt = np.radians(np.linspace(2.0, 0.0, 40)) / 2
    poses = np.column_stack([np.zeros(40), np.zeros(40), z, np.cos(tilt), np.sin(tilt), np.zeros(40), np.zeros(40)])
    engine.modes = reference
    ref = engine.query(poses)

    def rms(a, b):
        return float(np.sqrt(np.sum((a - b) ** 2) / np.sum(b ** 2)))

    rows = []
    for m in modes:
        engine.modes = m
        r = engine.query(poses)
        rows.append((m, rms(r["energy"], ref["energy"]), rms(r["force"], ref["force"]), rms(r["torque"], ref["torque"])))
    return rows


if __name__ == "__main__":
    print("m'        E error   F error   T error   (relative RMS against m' = 131072)")
    for m, e, f, t in sweep():
        print(f"{m:7d}  {100 * e:8.3f}% {100 * f:8.3f}% {100 * t:8.3f}%")
