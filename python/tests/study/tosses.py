"""Tosses the engine makes itself, for the fit-study tests: a 0.1 m box released over a
half-space from a known state (the velocity columns give it), simulated by `vcontact compare`
with a known model, its simulated poses written back as the record (as
tests/validation/toss_fixtures.hpp makes them in C++), so that the truth is a point of the
model fitted."""

import csv
import json
import math
import os
import subprocess

SIZE, MASS = 0.1, 0.37
INERTIA = MASS * 2 * SIZE ** 2 / 12  # kg m², a solid cube
POSE = ("x", "y", "z", "qw", "qx", "qy", "qz")
COLUMNS = ("t",) + POSE + ("vx", "vy", "vz", "wx", "wy", "wz")
# mu low enough that every toss slides to the end: a box that sticks and rests costs ten to a
# hundred times more to simulate (the rest on a soft face), which a quick test cannot afford.
TRUTH = {"format": "vcontact.model/1",
         "effects": {"stiffness": {"kv": 2e6}, "damping": {"a": 3.0}, "coulomb": {"mu": 0.1}}}
START = {"format": "vcontact.model/1",
         "effects": {"stiffness": {"kv": 2e6}, "damping": {"a": 1.5}, "coulomb": {"mu": 0.1}},
         "fixed": ["stiffness.kv", "coulomb.mu", "coulomb.v_s"]}


def _sidecar(name):
    return {"format": "vcontact.dataset/1", "name": name, "data": name + ".csv",
            "mode": "dynamic", "payload": {"shape": "box", "size": [SIZE] * 3},
            "plate": {"shape": "halfspace"},
            "payload_inertia": {"mass": MASS, "inertia": [INERTIA] * 3},
            "outputs": ["position", "attitude"], "noise": {"position": 2e-4, "attitude": 2e-3},
            "notes": "an engine-made toss (python/tests/study/tosses.py)"}


def _write(folder, name, rows):
    with open(os.path.join(folder, name + ".csv"), "w", encoding="utf-8") as f:
        f.write(",".join(COLUMNS) + "\n")
        for r in rows:
            f.write(",".join(repr(float(v)) for v in r) + "\n")
    with open(os.path.join(folder, name + ".json"), "w", encoding="utf-8") as f:
        json.dump(_sidecar(name), f, indent=1)


def make_tosses(binary, folder, count=4, duration=0.3, rate=100.0):
    """`count` tosses landing sliding in different directions and spins, as NAME.json/.csv in
    `folder`; the truth and a start half the true damping as truth.model.json and start.model.json."""
    os.makedirs(folder, exist_ok=True)
    work = os.path.join(folder, "_made")
    os.makedirs(work, exist_ok=True)
    truth = os.path.join(folder, "truth.model.json")
    with open(truth, "w", encoding="utf-8") as f:
        json.dump(TRUTH, f)
    with open(os.path.join(folder, "start.model.json"), "w", encoding="utf-8") as f:
        json.dump(START, f)
    for k in range(count):
        a, tilt = 0.7 * k, 0.1 * k
        state = [0.0, 0.0, 0.09 + 0.01 * k, math.cos(tilt / 2), math.sin(tilt / 2), 0.0, 0.0,
                 0.8 * math.cos(a), 0.8 * math.sin(a), -0.2, 0.0, 0.0, 1.0 + k]
        n = int(round(duration * rate)) + 1
        name = f"toss{k}"
        _write(work, name, [[i / rate] + state for i in range(n)])  # the times only
        out = os.path.join(work, name + ".out")
        subprocess.run([binary, "compare", os.path.join(work, name + ".json"), "--model", truth,
                        "--out", out], check=True, capture_output=True, text=True)
        with open(os.path.join(out, "trajectory.csv"), encoding="utf-8") as f:
            sim = list(csv.DictReader(f))
        _write(folder, name, [[float(r["t"])] + [float(r[c + "_sim"]) for c in POSE] + state[7:]
                              for r in sim])
    return folder
