#!/usr/bin/env python3
"""Writes the battery-box and fixture meshes of assets/scenarios/battery_box_fixture.json as ASCII STL:
non-convex x-z profiles extruded along y (closed, outward-oriented; caps by ear clipping).
Lengths in metres. Run: python3 scripts/extrude_profile.py (writes into assets/scenarios/meshes/)."""
import os

# Open-top tray: 4 mm base, 3 mm walls 20 mm high, two 4 mm alignment ribs 6 mm below the base.
BOX = [(-0.03, 0), (-0.022, 0), (-0.022, -0.006), (-0.018, -0.006), (-0.018, 0),
       (0.018, 0), (0.018, -0.006), (0.022, -0.006), (0.022, 0), (0.03, 0), (0.03, 0.02),
       (0.027, 0.02), (0.027, 0.004), (-0.027, 0.004), (-0.027, 0.02), (-0.03, 0.02)]
# Fixture block with two 4.8 mm slots, 8 mm deep, with 1.1 mm x 1.5 mm entry chamfers.
FIXTURE = [(-0.04, -0.02), (0.04, -0.02), (0.04, 0), (0.0235, 0), (0.0224, -0.0015),
           (0.0224, -0.008), (0.0176, -0.008), (0.0176, -0.0015), (0.0165, 0),
           (-0.0165, 0), (-0.0176, -0.0015), (-0.0176, -0.008), (-0.0224, -0.008),
           (-0.0224, -0.0015), (-0.0235, 0), (-0.04, 0)]


def cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def inside(p, a, b, c):
    return cross(a, b, p) > 0 and cross(b, c, p) > 0 and cross(c, a, p) > 0


def ear_clip(poly):
    """Triangles (index triples, counter-clockwise) of a simple counter-clockwise polygon."""
    idx = list(range(len(poly)))
    tris = []
    while len(idx) > 3:
        for k in range(len(idx)):
            i, j, l = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            a, b, c = poly[i], poly[j], poly[l]
            if cross(a, b, c) <= 0:
                continue
            if any(inside(poly[m], a, b, c) for m in idx if m not in (i, j, l)):
                continue
            tris.append((i, j, l))
            idx.pop(k)
            break
    tris.append(tuple(idx))
    return tris


def extrude(profile, width):
    """Triangles of the profile (x, z), counter-clockwise seen from -y, extruded over |y| <= w/2."""
    h = width / 2
    front = [(x, -h, z) for x, z in profile]   # y = -h face, outward normal -y
    back = [(x, h, z) for x, z in profile]     # y = +h face, outward normal +y
    tris = []
    n = len(profile)
    for i in range(n):
        j = (i + 1) % n
        tris.append((front[i], back[i], back[j]))
        tris.append((front[i], back[j], front[j]))
    for a, b, c in ear_clip(profile):
        tris.append((front[a], front[b], front[c]))
        tris.append((back[a], back[c], back[b]))
    return tris


def signed_volume(tris):
    return sum(a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
               + a[2] * (b[0] * c[1] - b[1] * c[0]) for a, b, c in tris) / 6.0


def write_stl(path, tris):
    if signed_volume(tris) < 0:
        tris = [(a, c, b) for a, b, c in tris]
    with open(path, "w") as f:
        f.write("solid part\n")
        for a, b, c in tris:
            f.write("facet normal 0 0 0\n outer loop\n")
            for p in (a, b, c):
                f.write("  vertex %.9g %.9g %.9g\n" % p)
            f.write(" endloop\nendfacet\n")
        f.write("endsolid part\n")


here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "scenarios", "meshes")
write_stl(os.path.join(here, "battery_box.stl"), extrude(BOX, 0.04))
write_stl(os.path.join(here, "fixture.stl"), extrude(FIXTURE, 0.06))
