"""E and |F| along a straight insertion of the default peg, at three m', with matplotlib.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/insertion_path.py [OUT.png]

Part 2 goes down the hole's axis from z = 10 to z = -5 (scene units, part 1's frame); the
figure shows the energy and the force's magnitude at each depth for each m', so one sees
what truncation does to the wrench the device would feel.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import snapfit  # noqa: E402


def insertion(scene_file="scenes/default.json", depths=np.linspace(10.0, -5.0, 121), modes=(1024, 4096, 16384)):
    """Energy (N,) and |F| (N,) at each depth for each m': {m': (energy, force)}."""
    engine = snapfit.Assembly(snapfit.load_scene(scene_file)).query_engine()
    poses = np.zeros((len(depths), 7))
    poses[:, 2] = depths
    poses[:, 3] = 1.0  # no rotation
    curves = {}
    for m in modes:
        engine.modes = m
        r = engine.query(poses)
        curves[m] = (r["energy"], np.linalg.norm(r["force"], axis=1))
    return depths, curves


def main(out="insertion_path.png"):
    depths, curves = insertion()
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
    for m, (energy, force) in curves.items():
        top.plot(depths, energy, label=f"m' = {m}")
        bottom.plot(depths, force, label=f"m' = {m}")
    top.set_ylabel("energy E")
    bottom.set_ylabel("|F| (engine units)")
    bottom.set_xlabel("depth z of part 2 (scene units; the peg enters the hole going down)")
    top.legend()
    top.set_title("The default peg along its insertion")
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(*sys.argv[1:2])
