"""A scripted device in Python driving a live session: the hand goes from the scene's start
down the hole's axis to the assembled pose over a few seconds (as an imprecise user would:
0.5 mm off the axis, 2 degrees tilted), while the loop renders the wrench at 1 kHz on its own
thread; the script prints the force it would send to a real device and the verdict.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/live_device.py
"""
import math
import time

import numpy as np

import snapfit


def pose(x, y, z, tilt_deg=0.0):
    """x, y, z, then the quaternion of a tilt about y (w, x, y, z)."""
    half = math.radians(tilt_deg) / 2
    return np.array([x, y, z, math.cos(half), 0.0, math.sin(half), 0.0])


def drive(session, seconds=3.0, start=(1.0, 0.0, 10.0), end=(0.5, 0.0, -20.0), tilt_deg=2.0, period_s=0.005):
    """Moves the held device pose in a straight line, then holds it at the end for a second.
    Returns one row per step: time, device z, part 2's z and |force sent|."""
    rows = []
    t0 = time.monotonic()
    while True:
        t = time.monotonic() - t0
        s = min(t / seconds, 1.0)
        x, y, z = (a + s * (b - a) for a, b in zip(start, end))
        session.hold_device_pose(pose(x, y, z, tilt_deg * (1 - s)))
        frame = session.latest()
        rows.append((t, z, frame["part_pose"][2], float(np.linalg.norm(frame["force_sent"]))))
        if t > seconds + 1.0:
            return np.array(rows)
        time.sleep(period_s)


def main():
    session = snapfit.LiveSession(snapfit.load_scene("scenes/default.json"), modes=4096, strategy="tricubic")
    session.start()
    try:
        rows = drive(session)
    finally:
        status = session.stop()
    for t, device_z, part_z, force in rows[:: max(1, len(rows) // 12)]:
        print(f"t {t:5.2f} s  device z {device_z:7.2f}  part z {part_z:7.2f}  |F sent| {force:6.3f} N")
    print(f"{status['frames']} frames, {status['misses']} misses; assembled: {status['assembled']} "
          f"(position error {status['position_error']:.3f} mm)")


if __name__ == "__main__":
    main()
