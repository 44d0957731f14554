#!/usr/bin/env python3
"""Writes the meshes of assets/scenarios/peg_jam.json as binary STL (metres, closed,
outward-oriented, shared edges made of the same vertices):

  peg_d10.stl        round peg, 10 mm across (a 64-gon prism of circumradius 5 mm), 30 mm
                     long, centred on its axis (z);
  block_hole_d10.stl block 40 x 40 x 20 mm, z in [-20, 0] mm, with a through hole of
                     circumradius 5.1 mm (64-gon) on the z axis: 0.094 mm of radial clearance
                     between the polygons' flats.

The block's faces around the hole join each corner of the hole polygon to the point of the
square outline at the same angle (64 is a multiple of 8, so the square's corners are among
them): one ring of quads, with no fan or second pass.

Run from the repository root: /usr/bin/python3 scripts/peg_hole_meshes.py
(writes into assets/scenarios/meshes/)."""
import math
import os
import struct

N_SEG = 64
PEG_RADIUS = 0.005
PEG_LENGTH = 0.030
HOLE_RADIUS = 0.0051
BLOCK_HALF = 0.020   # half the side of the square block
BLOCK_DEPTH = 0.020  # z from -BLOCK_DEPTH to 0
OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "scenarios",
                   "meshes")


def write_stl(path, points, tris):
    with open(path, "wb") as f:
        f.write(b"vcontact peg_hole_meshes.py".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            for i in t:
                f.write(struct.pack("<3f", *points[i]))
            f.write(struct.pack("<H", 0))


def quad(tris, a, b, c, d):
    """Two triangles of the quad a b c d, counter-clockwise seen from outside."""
    tris.append((a, b, c))
    tris.append((a, c, d))


def angles():
    return [2.0 * math.pi * k / N_SEG for k in range(N_SEG)]


def peg():
    """Prism of the 64-gon; the caps are fans about their centres."""
    h = PEG_LENGTH / 2
    points = [(0.0, 0.0, -h), (0.0, 0.0, h)]
    for a in angles():
        c, s = math.cos(a), math.sin(a)
        points += [(PEG_RADIUS * c, PEG_RADIUS * s, -h), (PEG_RADIUS * c, PEG_RADIUS * s, h)]
    tris = []
    for k in range(N_SEG):
        lo, hi = 2 + 2 * k, 3 + 2 * k
        lo2, hi2 = 2 + 2 * ((k + 1) % N_SEG), 3 + 2 * ((k + 1) % N_SEG)
        quad(tris, lo, lo2, hi2, hi)
        tris.append((1, hi, hi2))
        tris.append((0, lo2, lo))
    return points, tris


def block():
    """Ring of quads between the hole polygon and the square outline, at the top (z = 0) and
    bottom (z = -BLOCK_DEPTH), with the hole wall and the outer walls between them."""
    points = []
    for a in angles():
        c, s = math.cos(a), math.sin(a)
        r_out = BLOCK_HALF / max(abs(c), abs(s))
        for z in (-BLOCK_DEPTH, 0.0):
            points.append((r_out * c, r_out * s, z))
            points.append((HOLE_RADIUS * c, HOLE_RADIUS * s, z))
    # vertex 4k + {0: outer bottom, 1: inner bottom, 2: outer top, 3: inner top}
    tris = []
    for k in range(N_SEG):
        i, j = 4 * k, 4 * ((k + 1) % N_SEG)
        quad(tris, i + 0, j + 0, j + 2, i + 2)  # outer wall, normal away from the axis
        quad(tris, i + 1, i + 3, j + 3, j + 1)  # hole wall, normal towards the axis
        quad(tris, i + 2, j + 2, j + 3, i + 3)  # top, +z
        quad(tris, i + 0, i + 1, j + 1, j + 0)  # bottom, -z
    return points, tris


def main():
    os.makedirs(OUT, exist_ok=True)
    write_stl(os.path.join(OUT, "peg_d10.stl"), *peg())
    write_stl(os.path.join(OUT, "block_hole_d10.stl"), *block())


if __name__ == "__main__":
    main()
