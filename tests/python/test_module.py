"""`import snapfit` as a Python user would: scenes, an assembly, queries with numpy arrays,
errors as exceptions, and the same E, F and T as the C++ tool (`snapfit query`) gives."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

import snapfit

SCENE = "scenes/default.json"
TRANSLATION_SCENE = "scenes/peg_hole_translation.json"


@pytest.fixture(scope="module")
def assembly():
    return snapfit.Assembly(snapfit.load_scene(SCENE))


@pytest.fixture(scope="module")
def engine(assembly):
    e = assembly.query_engine()
    e.modes = 4096
    return e


def poses():
    # Part 2 at the hole's mouth and in it (the scene starts at z = 10), turned a little about x and z (x, y, z, qw, qx, qy, qz).
    turn = np.array([np.cos(0.02), np.sin(0.02) * 0.6, 0.0, np.sin(0.02) * 0.8])
    return np.array([[0.0, 0.0, 10.0, 1, 0, 0, 0],
                     [0.3, -0.2, 8.0, *turn],
                     [0.0, 0.1, 5.0, *turn]])


def test_scene_and_assembly(assembly):
    scene = assembly.scene
    assert scene.name == snapfit.load_scene(SCENE).name
    assert scene.units == "mm"
    assert assembly.spacing > 0
    assert len(assembly.fft_dims) == 3 and all(n > 0 for n in assembly.fft_dims)
    assert json.loads(scene.to_json())["part1"]


def test_query_shapes_and_dtypes(engine):
    r = engine.query(poses())
    assert engine.modes == 4096 and engine.modes <= engine.max_modes
    assert r["energy"].shape == (3,) and r["energy"].dtype == np.float64
    assert r["force"].shape == (3, 3) and r["torque"].shape == (3, 3)
    assert r["error_estimate"].shape == (3, 3)
    assert r["flags"].dtype == np.uint32 and not r["flags"].any()  # all inside the grid, all valid
    assert (r["energy"] != 0).all()
    assert (r["modes"] == 4096).all()
    assert np.isfinite(r["energy"]).all() and np.isfinite(r["force"]).all()
    # Beyond the padded box: zeros, flagged (query_outside_grid), as in C++.
    far = engine.query(np.array([[0.0, 0.0, 500.0, 1, 0, 0, 0]]))
    assert far["flags"][0] == 1 and far["energy"][0] == 0
    # One pose as a 1-D row gives one row.
    one = engine.query(poses()[1])
    assert one["energy"].shape == (1,)
    assert one["energy"][0] == r["energy"][1]


def test_same_results_as_the_tool(engine):
    """Bit for bit the C++ tool's E, F and T at the same poses and m' (its JSON holds every
    double exactly). The tool takes axis-angle in degrees: the axes here are unit vectors
    and the quaternion is made as Eigen makes it, with the same libm."""
    turns = [((1.0, 0.0, 0.0), 0.0), ((0.0, 1.0, 0.0), 1.5), ((0.0, 0.0, 1.0), -2.0), ((1.0, 0.0, 0.0), 3.0)]
    positions = [(0.0, 0.0, 10.0), (0.3, -0.2, 8.0), (0.0, 0.1, 5.0), (-0.2, 0.0, 2.0)]
    args = [os.environ["SNAPFIT_CLI"], "query", SCENE, "--modes", "4096"]
    rows = []
    for (x, y, z), (axis, degrees) in zip(positions, turns):
        args += ["--pose", ",".join(repr(v) for v in (x, y, z, *axis, degrees))]
        half = 0.5 * (degrees * math.pi / 180.0)
        rows.append([x, y, z, math.cos(half), *(math.sin(half) * a for a in axis)])
    lines = subprocess.run(args, check=True, capture_output=True, text=True).stdout.splitlines()
    tool = [json.loads(line) for line in lines]
    assert len(tool) == len(rows)
    mine = engine.query(np.array(rows))
    assert not mine["flags"].any()
    for i, t in enumerate(tool):
        assert mine["energy"][i] == t["energy"]
        assert mine["force"][i].tolist() == t["force"]
        assert mine["torque"][i].tolist() == t["torque"]


def test_bad_input_raises_clear_errors(engine):
    with pytest.raises(ValueError, match="7 columns"):
        engine.query(np.zeros((2, 5)))
    with pytest.raises(ValueError, match="pose 1 is not finite"):
        engine.query(np.array([[0, 0, 25, 1, 0, 0, 0], [0, np.nan, 25, 1, 0, 0, 0]]))
    with pytest.raises(ValueError, match="quaternion has length"):
        engine.query(np.array([[0, 0, 25, 2, 0, 0, 0]]))
    with pytest.raises(ValueError, match="turns part 2"):
        engine.query(np.zeros((2, 3)))
    with pytest.raises(snapfit.Error, match="no_such_scene.json"):
        snapfit.load_scene("no_such_scene.json")
    with pytest.raises(ValueError, match="strategy must be"):
        snapfit.Assembly(snapfit.load_scene(SCENE)).query_engine("cubic")


def test_scene_from_dict_names_the_bad_field():
    with open(SCENE) as f:
        d = json.load(f)
    assert snapfit.scene_from_dict(d).name == d["name"]
    d["part2"]["procedural"]["radius"] = -1
    with pytest.raises(snapfit.Error, match=r"part2\.procedural\.radius"):
        snapfit.scene_from_dict(d)


def test_translation_only_takes_positions():
    engine = snapfit.Assembly(snapfit.load_scene(TRANSLATION_SCENE)).query_engine()
    assert engine.translation_only
    r = engine.query(np.array([[0.0, 0.0, 25.0], [0.0, 0.0, 10.0]]))
    assert r["force"].shape == (2, 3)
    full = engine.query(np.array([[0.0, 0.0, 10.0, 1, 0, 0, 0]]))
    assert full["energy"][0] == r["energy"][1]


def test_auto_tune_sets_and_saves_m(assembly):
    engine = assembly.query_engine()
    t = snapfit.auto_tune(assembly, engine, repetitions=50)
    # The sweep stops at the first m' past the budget: on a loaded machine that may be the first.
    assert t["modes"].shape == t["p99_ms"].shape == t["p50_ms"].shape and len(t["modes"]) >= 1
    assert (np.diff(t["modes"]) > 0).all() and (t["p99_ms"] >= t["p50_ms"]).all() and (t["p50_ms"] > 0).all()
    assert 1 <= t["chosen_modes"] <= engine.max_modes and t["budget_ms"] == 1.0
    assert engine.modes == engine.max_modes  # the engine keeps its m', as in C++
    # Kept only when some m' fits: a tuning in which none does is more likely a busy machine.
    assert os.path.exists(t["file"]) == bool(t["fits"])
    if t["fits"]:
        # Again: read from the tuning file, the same choice.
        assert snapfit.auto_tune(assembly, engine, repetitions=50)["chosen_modes"] == t["chosen_modes"]


def test_run_job_returns_the_loop_as_arrays(tmp_path):
    job = snapfit.run_job(snapfit.load_scene(SCENE), modes=2048, strategy="tricubic", simulated_time=True,
                          out=str(tmp_path / "run"))
    loop = job["loop"]
    n = loop["frames"]
    assert n > 1000 and loop["time_s"].shape == (n,) and loop["part_pose"].shape == (n, 7)
    assert loop["force_sent"].shape == (n, 3) and (loop["modes"] == 2048).all()
    assert (np.diff(loop["time_s"]) > 0).all()
    assert np.allclose(np.linalg.norm(loop["part_pose"][:, 3:], axis=1), 1.0)
    assert job["evaluated"] and job["assembled"]
    assert job["final_position_error"] < 0.5
    assert job["strategy"] == "6dof energy force torque tricubic"
    # The report folder, as `snapfit run --out` writes it, with the same verdict.
    assert "report.html" in job["report"] and "summary.json" in job["report"]
    with open(tmp_path / "run" / "summary.json") as f:
        summary = json.load(f)
    assert summary["haptic_loop"]["assembled"] is True and summary["haptic_loop"]["frames"] == n


def test_time_batch_gives_one_time_per_repeat(engine):
    seconds = engine._time_batch(poses(), 3)
    assert len(seconds) == 3 and all(s > 0 for s in seconds)


def test_part_mesh_matches_scene_check():
    """The meshes as arrays: their volume by the divergence theorem in numpy against the
    volume `snapfit scene-check` prints (the C++ mass properties)."""
    scene = snapfit.load_scene(SCENE)
    out = subprocess.run([os.environ["SNAPFIT_CLI"], "scene-check", SCENE], check=True, capture_output=True,
                         text=True).stdout
    volumes = [float(line.split("volume ")[1].split()[0]) for line in out.splitlines() if "volume " in line]
    for part, volume in zip((1, 2), volumes):
        v, t = snapfit.part_mesh(scene, part)
        assert v.dtype == np.float64 and t.dtype == np.int32 and v.shape[1] == 3 and t.shape[1] == 3
        assert t.min() >= 0 and t.max() < len(v)
        a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
        mine = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6
        assert mine == pytest.approx(volume, rel=1e-5)  # scene-check prints 6 digits
    with pytest.raises(snapfit.Error, match="part must be 1 or 2"):
        snapfit.part_mesh(scene, 3)


def test_part_fields_as_arrays():
    scene = snapfit.load_scene(SCENE)
    f = snapfit.part_fields(scene, 2)
    w, s = f["winding"], f["skeletal_density"]
    assert w.ndim == 3 and w.dtype == np.float32 and s.shape == w.shape
    # The winding number is about 1 inside the peg and 0 far outside: its grid point at the
    # axis, mid-length, against a corner of the padded grid.
    nz, ny, nx = w.shape
    ox, oy, oz = f["origin"]
    h = f["spacing"]
    i, j, k = round(-ox / h), round(-oy / h), round((15 - oz) / h)  # (0, 0, 15): inside the peg
    assert w[k, j, i] == pytest.approx(1.0, abs=0.05)
    assert abs(w[0, 0, 0]) < 0.05
    assert f["winding_bound"].shape == w.shape


def test_search_matches_the_tool():
    scene = snapfit.load_scene(SCENE)
    mine = snapfit.search(scene, rotations=8, top=1, map_fft="clfft")
    out = subprocess.run([os.environ["SNAPFIT_CLI"], "search", SCENE, "--rotations", "8", "--top", "1", "--map-fft",
                          "clfft"], check=True, capture_output=True, text=True).stdout
    tool = json.loads(next(line for line in out.splitlines() if line.startswith("{")))
    assert mine["rotations"].shape[1] == 4 and len(mine["best_energy"]) == len(mine["rotations"])
    assert np.allclose(np.linalg.norm(mine["rotations"], axis=1), 1.0)
    assert mine["poses"].shape == (1, 7) and mine["refined_poses"].shape == (1, 7)
    assert mine["energy"][0] == tool["energy"]
    assert mine["poses"][0, :3].tolist() == tool["position"]
    assert mine["energy"][0] == mine["best_energy"].min()


def test_accuracy_follows_its_rule():
    report = snapfit.accuracy(snapfit.Assembly(snapfit.load_scene(SCENE)), poses=4, repetitions=40)
    strategies = report["strategies"]
    assert [s["name"] for s in strategies] == ["6dof energy force torque tricubic", "6dof energy force torque trilinear",
                                               "6dof energy force torque exact-product background"]
    assert report["reference_modes"] > max(s["modes"] for s in strategies)
    for s in strategies:
        assert s["modes"] > 0 and s["energy_error"] >= 0 and len(s["estimate_coverage"]) == 3

    def rendered(s):
        return max(s["force_error"], s["torque_error"])

    best = report["best"]
    fitting = [s for s in strategies if s["fits"]] or strategies
    assert rendered(strategies[best]) == min(rendered(s) for s in fitting)
    assert report["why"]


def test_strategies_near_far_closest_to_the_exact_reference():
    """At the same small m', the near-far split is closer to the exact, untruncated sum than the
    tricubic sum (docs/design.md "Near and far"); without the near field it is refused."""
    scene = snapfit.load_scene(SCENE)
    assembly = snapfit.Assembly(scene, near_field=True)
    p = poses()
    reference = assembly.query_engine("exact-product")
    reference.modes = reference.max_modes
    ref = reference.query(p)
    errors = {}
    for strategy in ("tricubic", "near-far"):
        engine = assembly.query_engine(strategy)
        engine.modes = 8192
        r = engine.query(p)
        errors[strategy] = np.linalg.norm(r["force"] - ref["force"]) / np.linalg.norm(ref["force"])
    assert errors["near-far"] < 0.5 * errors["tricubic"], errors
    with pytest.raises(snapfit.Error):
        snapfit.Assembly(scene).query_engine("near-far")
    with pytest.raises(ValueError, match="only its lines"):
        snapfit.Assembly(snapfit.load_scene(TRANSLATION_SCENE)).query_engine("exact-product")
