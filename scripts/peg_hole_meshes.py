#!/usr/bin/env python3
"""Writes the meshes of assets/scenarios/peg_jam.json as binary STL (metres, closed,
outward-oriented, shared edges made of the same vertices):

  peg_d10.stl        round peg, 10 mm across (a 64-gon prism of circumradius 5 mm), 30 mm
                     long, centred on its axis (z);
  block_hole_d10.stl block 40 x 40 x 20 mm, z in [-20, 0] mm, with a through hole of
                     circumradius 5.1 mm (64-gon) on the z axis: 0.094 mm of radial clearance
                     between the polygons' flats.

With --chamfer MM it writes instead

  block_hole_d10_chamfer<MM>.stl  the same block whose hole is widened at the top by a 45 degree
                     chamfer MM deep: the hole's circumradius grows from 5.1 mm at z = -MM
                     to 5.1 + MM at z = 0; with --blind DEPTH (mm) as well the hole is blind,
                     DEPTH deep with a flat floor, and the file is
                     block_hole_d10_chamfer<MM>_blind<DEPTH>.stl
                     (assets/scenarios/peg_insertion.json uses --chamfer 1 --blind 8).

The block's faces around the hole join each corner of the hole polygon to the point of the
square outline at the same angle (64 is a multiple of 8, so the square's corners are among
them): one ring of quads, with no fan or second pass.

Run from the repository root: /usr/bin/python3 scripts/peg_hole_meshes.py [--chamfer MM]
(writes into assets/scenarios/meshes/)."""
import argparse
import math
import os

from stl_writer import write_binary_stl

N_SEG = 64
PEG_RADIUS = 0.005
PEG_LENGTH = 0.030
HOLE_RADIUS = 0.0051
BLOCK_HALF = 0.020   # half the side of the square block
BLOCK_DEPTH = 0.020  # z from -BLOCK_DEPTH to 0
OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "scenarios",
                   "meshes")


def write_stl(path, points, tris):
    write_binary_stl(path, points, tris, "vcontact peg_hole_meshes.py")


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


def block(chamfer=0.0):
    """Ring of quads between the hole polygon and the square outline, at the top (z = 0) and
    bottom (z = -BLOCK_DEPTH), with the hole wall and the outer walls between them; with a
    chamfer, the hole's top ring is wider and a second ring at z = -chamfer joins the cone
    of the chamfer to the hole wall."""
    points = []
    for a in angles():
        c, s = math.cos(a), math.sin(a)
        r_out = BLOCK_HALF / max(abs(c), abs(s))
        for z in (-BLOCK_DEPTH, 0.0):
            points.append((r_out * c, r_out * s, z))
            r_in = HOLE_RADIUS + (chamfer if z == 0.0 else 0.0)
            points.append((r_in * c, r_in * s, z))
        if chamfer > 0.0:
            points.append((HOLE_RADIUS * c, HOLE_RADIUS * s, -chamfer))
    # vertex m k + {0: outer bottom, 1: inner bottom, 2: outer top, 3: inner top,
    # 4: the chamfer's lower edge}, m = 5 with a chamfer and 4 without
    m = 5 if chamfer > 0.0 else 4
    tris = []
    for k in range(N_SEG):
        i, j = m * k, m * ((k + 1) % N_SEG)
        quad(tris, i + 0, j + 0, j + 2, i + 2)  # outer wall, normal away from the axis
        if chamfer > 0.0:
            quad(tris, i + 1, i + 4, j + 4, j + 1)  # hole wall, normal towards the axis
            quad(tris, i + 4, i + 3, j + 3, j + 4)  # chamfer cone, up and inwards
        else:
            quad(tris, i + 1, i + 3, j + 3, j + 1)  # hole wall, normal towards the axis
        quad(tris, i + 2, j + 2, j + 3, i + 3)  # top, +z
        quad(tris, i + 0, i + 1, j + 1, j + 0)  # bottom, -z
    return points, tris


def fan(tris, centre, ring, up):
    """Triangles from `centre` to consecutive vertices of `ring`, facing +z when `up`."""
    for k in range(len(ring)):
        a, b = ring[k], ring[(k + 1) % len(ring)]
        tris.append((centre, a, b) if up else (centre, b, a))


def blind_block(chamfer, depth):
    """The chamfered block with a blind hole `depth` deep: the hole wall ends in a flat floor
    (a fan facing up) and the block's bottom is a full square (a fan facing down)."""
    points, rings = [], {"outer_bottom": [], "outer_top": [], "inner_top": [], "chamfer": [],
                         "floor": []}
    for a in angles():
        c, s = math.cos(a), math.sin(a)
        r_out = BLOCK_HALF / max(abs(c), abs(s))
        for name, r, z in (("outer_bottom", r_out, -BLOCK_DEPTH), ("outer_top", r_out, 0.0),
                           ("inner_top", HOLE_RADIUS + chamfer, 0.0),
                           ("chamfer", HOLE_RADIUS, -chamfer), ("floor", HOLE_RADIUS, -depth)):
            rings[name].append(len(points))
            points.append((r * c, r * s, z))
    floor_centre, bottom_centre = len(points), len(points) + 1
    points += [(0.0, 0.0, -depth), (0.0, 0.0, -BLOCK_DEPTH)]
    tris = []
    R = rings
    for k in range(N_SEG):
        j = (k + 1) % N_SEG
        quad(tris, R["outer_bottom"][k], R["outer_bottom"][j], R["outer_top"][j],
             R["outer_top"][k])  # outer wall
        quad(tris, R["outer_top"][k], R["outer_top"][j], R["inner_top"][j],
             R["inner_top"][k])  # top, +z
        quad(tris, R["chamfer"][k], R["inner_top"][k], R["inner_top"][j],
             R["chamfer"][j])  # chamfer cone, up and inwards
        quad(tris, R["floor"][k], R["chamfer"][k], R["chamfer"][j],
             R["floor"][j])  # hole wall, towards the axis
    fan(tris, floor_centre, R["floor"], up=True)
    fan(tris, bottom_centre, R["outer_bottom"], up=False)
    return points, tris


def main():
    parser = argparse.ArgumentParser(description="Peg and block meshes (see the module text).")
    parser.add_argument("--chamfer", type=float, default=0.0,
                        help="write the block with a 45 degree chamfer this deep (mm) instead")
    parser.add_argument("--blind", type=float, default=0.0,
                        help="with --chamfer: a blind hole this deep (mm) with a flat floor")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    if args.blind > 0.0:
        if not 0.0 < args.chamfer < args.blind < BLOCK_DEPTH * 1000.0:
            parser.error("--blind needs --chamfer, and 0 < chamfer < blind < 20 (mm)")
        name = "block_hole_d10_chamfer%g_blind%g.stl" % (args.chamfer, args.blind)
        write_stl(os.path.join(OUT, name), *blind_block(args.chamfer / 1000.0, args.blind / 1000.0))
        return
    if args.chamfer > 0.0:
        name = "block_hole_d10_chamfer%g.stl" % args.chamfer
        write_stl(os.path.join(OUT, name), *block(args.chamfer / 1000.0))
        return
    write_stl(os.path.join(OUT, "peg_d10.stl"), *peg())
    write_stl(os.path.join(OUT, "block_hole_d10.stl"), *block())


if __name__ == "__main__":
    main()
