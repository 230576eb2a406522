"""The examples in examples/python run, and what they show holds."""
import numpy as np

import snapfit

import insertion_path
import modes_sweep


def test_insertion_path_draws_and_the_peg_is_pulled_in(tmp_path):
    depths, curves = insertion_path.insertion(depths=np.linspace(10.0, -5.0, 31), modes=(4096, 16384))
    for energy, force in curves.values():
        assert energy.shape == (31,) and force.shape == (31,)
        assert np.isfinite(energy).all() and (force >= 0).all()
        assert energy[-1] < energy[0]  # deeper in the hole, lower energy: the fit pulls the part home
    out = tmp_path / "insertion.png"
    insertion_path.main(str(out))
    assert out.stat().st_size > 10000


def test_modes_sweep_error_falls_with_m():
    rows = modes_sweep.sweep(modes=(512, 2048, 8192), reference=65536)
    errors = np.array([[e, f] for _, e, f, _ in rows])
    assert (np.diff(errors, axis=0) < 0).all()  # E and F errors fall as m' grows


def test_live_device_pushes_the_peg_home():
    import live_device

    session = snapfit.LiveSession(snapfit.load_scene("scenes/default.json"), modes=2048, strategy="tricubic")
    session.start()
    try:
        rows = live_device.drive(session, seconds=2.0)
        during = session.status()
    finally:
        status = session.stop()
    assert during["frames"] > 500 and status["frames"] >= during["frames"]
    # The part followed the hand into the hole: it ends near the assembled pose.
    assert rows[0][2] > 5 and rows[-1][2] < -15
    assert status["evaluated"] and status["assembled"], status
    assert max(r[3] for r in rows) > 0  # the loop sent a force on the way in
