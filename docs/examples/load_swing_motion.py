#!/usr/bin/env python3
"""Writes a motion CSV for `vcontact synth --motion` (docs/EXTENDING.md, example a).

The punch of the synth profiles (cylinder R = 10 mm, L = 20 mm, origin at its centre, face
down) slides along x at 5 mm/s while its depth in the plate swings between 10 and 30 nm, three
cycles in 3 s: the load varies while it slides, so that a friction coefficient that grows
with the load can be told from a constant one. Plain Python, no packages.

Usage: python3 load_swing_motion.py OUT.csv [SAMPLES]
"""
import math
import sys

HALF_LENGTH = 0.01  # m: the punch's origin height when its face touches the plate
DEPTH = 20e-9  # m: mean depth
SWING = 0.5  # depth swings by ±50 %
SPEED = 5e-3  # m/s along x
DURATION = 3.0  # s
CYCLES = 3


def main():
    out = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 1500
    w = 2.0 * math.pi * CYCLES / DURATION
    with open(out, "w") as f:
        f.write("t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n")
        for i in range(n):
            t = DURATION * i / (n - 1)
            depth = DEPTH * (1.0 + SWING * math.sin(w * t))
            vz = -DEPTH * SWING * w * math.cos(w * t)
            row = [t, SPEED * t, 0.0, HALF_LENGTH - depth, 1, 0, 0, 0, SPEED, 0.0, vz, 0, 0, 0]
            f.write(",".join(repr(float(v)) for v in row) + "\n")


if __name__ == "__main__":
    main()
