#!/usr/bin/env python3
"""A device program's end of snapfit's device bridge (docs/haptics.md "The device bridge").

No build and no dependency beyond Python 3's standard library. As a module:

    from snapfit_bridge import Bridge
    bridge = Bridge(port=8766)                       # `snapfit serve` prints the port
    bridge.send_state(position, quaternion_wxyz)     # every frame of your device's loop
    for wrench in bridge.receive():                  # what the session's loop sent back
        render(wrench.force, wrench.torque)          # N and N m, in part 1's frame

As a program it plays a scene's scripted trajectory as if a hand moved the device, at a
fixed rate, and prints what came back (round-trip times, the last wrench) as JSON:

    python3 examples/bridge/snapfit_bridge.py --port 8766 --scene scenes/default.json
"""
import argparse
import json
import math
import select
import socket
import struct
import sys
import time
from collections import namedtuple

VERSION = 1
MAGIC = b"SNFB"
STATE = struct.Struct("<4sHHI3d4d3d3d")          # 116 bytes: kind 1
WRENCH = struct.Struct("<4sHHII3d3ddfI")         # 80 bytes: kind 2
HEADER = struct.Struct("<4sHH")                  # every datagram starts with it; a refusal (kind 3)
LATE, CONTACT, FLAGGED, SANITISED = 1, 2, 4, 8   # bits of Wrench.flags

Wrench = namedtuple("Wrench", "sequence frame force torque energy fade flags")


class Refused(RuntimeError):
    """The session has another client: its message says which."""


class Bridge:
    def __init__(self, port, host="127.0.0.1"):
        self.address = (host, port)
        self.socket = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.socket.setblocking(False)
        self.sequence = 0

    def send_state(self, position, quaternion, velocity=(0, 0, 0), angular_velocity=(0, 0, 0)):
        """The device's pose (scene units; quaternion w, x, y, z) and velocities, in part 1's frame."""
        self.sequence = (self.sequence + 1) & 0xFFFFFFFF
        self.socket.sendto(STATE.pack(MAGIC, VERSION, 1, self.sequence, *position, *quaternion, *velocity,
                                      *angular_velocity), self.address)
        return self.sequence

    def send_bytes(self, data):
        self.socket.sendto(data, self.address)

    def receive(self):
        """Every wrench waiting, oldest first; raises Refused when the session turned this client away."""
        out = []
        while True:
            try:
                data = self.socket.recv(2048)
            except BlockingIOError:
                return out
            magic, version, kind = HEADER.unpack_from(data)
            if magic != MAGIC or version != VERSION:
                continue
            if kind == 3:
                (length,) = struct.unpack_from("<I", data, HEADER.size)
                raise Refused(data[12:12 + length].decode("utf-8", "replace"))
            if kind == 2 and len(data) == WRENCH.size:
                f = WRENCH.unpack(data)
                out.append(Wrench(f[3], f[4], f[5:8], f[8:11], f[11], f[12], f[13]))


def scene_trajectory(path):
    """The scene's keyframes as (time_s, position, quaternion w x y z)."""
    with open(path) as f:
        scene = json.load(f)
    frames = []
    for k in scene["trajectory"]["keyframes"]:
        r = k.get("rotation", {})
        if "quaternion" in r:
            q = r["quaternion"]
        else:
            axis, angle = r.get("axis", [0, 0, 1]), math.radians(r.get("angle_deg", 0))
            n = math.sqrt(sum(a * a for a in axis)) or 1
            s = math.sin(angle / 2)
            q = [math.cos(angle / 2)] + [s * a / n for a in axis]
        frames.append((k["time_s"], k["position"], q))
    return frames


def pose_at(frames, t):
    """Linear in position, normalised linear in the quaternion, held after the last keyframe."""
    if t <= frames[0][0]:
        return frames[0][1], frames[0][2]
    for (t0, p0, q0), (t1, p1, q1) in zip(frames, frames[1:]):
        if t <= t1:
            f = (t - t0) / (t1 - t0) if t1 > t0 else 1
            q = [a + f * (b - a) for a, b in zip(q0, q1)]
            n = math.sqrt(sum(c * c for c in q))
            return [a + f * (b - a) for a, b in zip(p0, p1)], [c / n for c in q]
    return frames[-1][1], frames[-1][2]


def percentile(values, q):
    if not values:
        return None
    v = sorted(values)
    return v[min(len(v) - 1, max(0, math.ceil(q * len(v)) - 1))]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--port", type=int, required=True, help="the session's bridge port (snapfit serve prints it)")
    parser.add_argument("--scene", required=True, help="play this scene's trajectory as the device's motion")
    parser.add_argument("--rate", type=float, default=1000, help="states per second (default 1000)")
    parser.add_argument("--settle", type=float, default=1.0, help="seconds to hold the last keyframe (default 1)")
    args = parser.parse_args()
    frames = scene_trajectory(args.scene)
    bridge = Bridge(args.port)
    duration = frames[-1][0] - frames[0][0] + args.settle
    total = int(round(duration * args.rate))  # a fixed count, however late this process runs
    sent_at, round_trips, wrenches, last = {}, [], 0, None
    start = time.perf_counter()
    n = 0
    try:
        while True:
            due = start + n / args.rate
            # Between sends wait on the socket, so a wrench is timed when it arrives.
            while (left := due - time.perf_counter()) > 0:
                if not select.select([bridge.socket], [], [], left)[0]:
                    break
                for w in bridge.receive():
                    wrenches += 1
                    last = w
                    if w.sequence in sent_at:  # the first wrench computed from that state
                        round_trips.append(1e3 * (time.perf_counter() - sent_at.pop(w.sequence)))
                        for older in [s for s in sent_at if s < w.sequence]:  # states the loop skipped
                            del sent_at[older]
            if n >= total:
                break
            position, quaternion = pose_at(frames, frames[0][0] + n / args.rate)  # the state's own time
            sent_at[bridge.sequence + 1] = time.perf_counter()
            bridge.send_state(position, quaternion)
            n += 1
    except Refused as e:
        print(json.dumps({"refused": str(e)}))
        return 3
    print(json.dumps({
        "states": n, "seconds": time.perf_counter() - start, "wrenches": wrenches,
        "round_trip_ms_p50": percentile(round_trips, 0.5), "round_trip_ms_p99": percentile(round_trips, 0.99),
        "last_force": list(last.force) if last else None, "last_fade": last.fade if last else None,
    }))
    return 0


if __name__ == "__main__":
    sys.exit(main())
