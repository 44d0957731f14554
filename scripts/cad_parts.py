#!/usr/bin/env python3
"""Writes the CAD-like parts of assets/scenarios/cad_tray_drop.json as binary STL (metres, closed,
outward-oriented, every shared edge made of the same vertices):

  tray_10k.stl     open-top tray 60 x 40 x 20 mm (4 mm floor, 3 mm walls) with two
                   4.8 mm alignment pins 6 mm long under the base, 1 mm x 0.4 mm tip chamfer;
  fixture_10k.stl  block 80 x 60 x 20 mm with two 5.2 mm holes 8 mm deep for the pins,
                   1 mm x 1 mm entry chamfers.

The curved features are finely faceted (128 segments), as an STL export of a CAD model is:
about 10k triangles each. Run: python3 scripts/cad_parts.py (writes into assets/scenarios/meshes/)."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from stl_writer import write_binary_stl  # noqa: E402 (the shared writer, beside this script)

N_SEG = 128          # segments around every circle
PIN_X = 0.020        # pins and holes at (±PIN_X, 0)


class Mesh:
    def __init__(self):
        self.index = {}
        self.points = []
        self.tris = []

    def v(self, p):
        key = tuple(round(c, 12) for c in p)
        if key not in self.index:
            self.index[key] = len(self.points)
            self.points.append(key)
        return self.index[key]

    def tri(self, a, b, c, outward):
        """Adds triangle (a, b, c), ordered so that its normal points along outward(centroid)."""
        ia, ib, ic = self.v(a), self.v(b), self.v(c)
        if len({ia, ib, ic}) < 3:
            return
        pa, pb, pc = self.points[ia], self.points[ib], self.points[ic]
        u = [pb[k] - pa[k] for k in range(3)]
        w = [pc[k] - pa[k] for k in range(3)]
        n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        centroid = [(pa[k] + pb[k] + pc[k]) / 3 for k in range(3)]
        d = outward(centroid)
        if sum(n[k] * d[k] for k in range(3)) < 0:
            ib, ic = ic, ib
        self.tris.append((ia, ib, ic))

    def quad(self, a, b, c, d, outward):
        self.tri(a, b, c, outward)
        self.tri(a, c, d, outward)

    def write_stl(self, path):
        write_binary_stl(path, self.points, self.tris, "vcontact cad_parts.py")


def const(d):
    return lambda _p: d


def lin(a, b, t):
    return a + (b - a) * t


def grid(mesh, corner, du, dv, nu, nv, outward):
    """Planar rectangle corner + s du + t dv, s, t in [0, 1], as nu x nv quads."""
    def p(i, j):
        return tuple(corner[k] + du[k] * i / nu + dv[k] * j / nv for k in range(3))
    for i in range(nu):
        for j in range(nv):
            mesh.quad(p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1), outward)


def rect_ring(x0, x1, y0, y1, nx, ny):
    """Boundary points of a rectangle, counter-clockwise from (x0, y0), nx/ny per side."""
    pts = [(lin(x0, x1, i / nx), y0) for i in range(nx)]
    pts += [(x1, lin(y0, y1, j / ny)) for j in range(ny)]
    pts += [(lin(x1, x0, i / nx), y1) for i in range(nx)]
    pts += [(x0, lin(y1, y0, j / ny)) for j in range(ny)]
    return pts


def circle(cx, cy, r):
    return [(cx + r * math.cos(2 * math.pi * k / N_SEG), cy + r * math.sin(2 * math.pi * k / N_SEG))
            for k in range(N_SEG)]


def annulus_zip(mesh, outer, inner, centre, z, outward):
    """Planar region between a star-shaped outer ring and an inner ring about `centre`,
    both counter-clockwise, at height z: triangles zipped in order of angle."""
    def ang(p):
        return math.atan2(p[1] - centre[1], p[0] - centre[0]) % (2 * math.pi)
    def start(ring):
        k = min(range(len(ring)), key=lambda i: ang(ring[i]))
        return ring[k:] + ring[:k]
    o, i = start(outer), start(inner)
    o, i = o + [o[0]], i + [i[0]]
    a, b = 0, 0
    def key(ring, k):
        return ang(ring[k]) if k < len(ring) - 1 else 2 * math.pi
    while a < len(o) - 1 or b < len(i) - 1:
        advance_outer = b == len(i) - 1 or (a < len(o) - 1 and key(o, a + 1) <= key(i, b + 1))
        if advance_outer:
            mesh.tri((*o[a], z), (*o[a + 1], z), (*i[b], z), outward)
            a += 1
        else:
            mesh.tri((*o[a], z), (*i[b + 1], z), (*i[b], z), outward)
            b += 1


def plate_with_holes(mesh, x0, x1, y0, y1, nx, ny, r, z, outward):
    """Rectangle minus discs of radius r at (±PIN_X, 0), split at x = 0 into two halves."""
    for lo, hi, cx in ((x0, 0.0, -PIN_X), (0.0, x1, PIN_X)):
        annulus_zip(mesh, rect_ring(lo, hi, y0, y1, nx // 2, ny), circle(cx, 0.0, r),
                    (cx, 0.0), z, outward)


def revolve(mesh, cx, profile, outward_sign):
    """Surface of revolution about the vertical axis through (cx, 0): profile is a list of
    (r, z); outward_sign +1 for a solid pin (normal away from the axis), -1 for a hole."""
    for (r0, z0), (r1, z1) in zip(profile, profile[1:]):
        a = circle(cx, 0.0, r0)
        b = circle(cx, 0.0, r1)
        for k in range(N_SEG):
            m = (k + 1) % N_SEG
            def out(p, sign=outward_sign, zc=(z0 + z1) / 2, slope=(r1 - r0), dz=(z1 - z0)):
                # radial normal of the cone, tilted by its slope
                rx, ry = p[0] - cx, p[1]
                rn = math.hypot(rx, ry) or 1.0
                nz = -slope * math.copysign(1.0, dz) if dz else 0.0
                nr = abs(dz)
                return (sign * nr * rx / rn, sign * nr * ry / rn, sign * nz)
            mesh.quad((*a[k], z0), (*a[m], z0), (*b[m], z1), (*b[k], z1), out)


def disc(mesh, cx, r, z, rings, normal_z):
    """Flat disc at height z with concentric rings, normal ±z."""
    radii = [r * (rings - j) / rings for j in range(rings)]
    for r0, r1 in zip(radii, radii[1:]):
        annulus_zip(mesh, circle(cx, 0.0, r0), circle(cx, 0.0, r1), (cx, 0.0), z,
                    const((0, 0, normal_z)))
    inner = circle(cx, 0.0, radii[-1])
    for k in range(N_SEG):
        mesh.tri((cx, 0.0, z), (*inner[k], z), (*inner[(k + 1) % N_SEG], z),
                 const((0, 0, normal_z)))


def steps(a, b, n):
    return [lin(a, b, j / n) for j in range(n + 1)]


def tray():
    m = Mesh()
    X, Y, H, WALL, FLOOR = 0.030, 0.020, 0.020, 0.003, 0.004
    nx, ny, nz = 24, 16, 8
    r_pin, r_tip, pin_len, chamfer = 0.0024, 0.0020, 0.006, 0.001
    plate_with_holes(m, -X, X, -Y, Y, nx, ny, r_pin, 0.0, const((0, 0, -1)))
    for cx in (-PIN_X, PIN_X):
        profile = [(r_pin, z) for z in steps(0.0, -(pin_len - chamfer), 10)][:-1]
        profile += [(lin(r_pin, r_tip, t), lin(-(pin_len - chamfer), -pin_len, t))
                    for t in (0.0, 0.25, 0.5, 0.75, 1.0)]
        revolve(m, cx, profile, +1)
        disc(m, cx, r_tip, -pin_len, 4, -1)
    # outer walls
    grid(m, (-X, -Y, 0), (2 * X, 0, 0), (0, 0, H), nx, nz, const((0, -1, 0)))
    grid(m, (X, -Y, 0), (0, 2 * Y, 0), (0, 0, H), ny, nz, const((1, 0, 0)))
    grid(m, (X, Y, 0), (-2 * X, 0, 0), (0, 0, H), nx, nz, const((0, 1, 0)))
    grid(m, (-X, Y, 0), (0, -2 * Y, 0), (0, 0, H), ny, nz, const((-1, 0, 0)))
    # rim: strip between the outer and the pocket rectangle at the top
    x, y = X - WALL, Y - WALL
    outer, inner = rect_ring(-X, X, -Y, Y, nx, ny), rect_ring(-x, x, -y, y, nx, ny)
    for k in range(len(outer)):
        j = (k + 1) % len(outer)
        m.quad((*outer[k], H), (*outer[j], H), (*inner[j], H), (*inner[k], H), const((0, 0, 1)))
    # pocket walls (normals into the pocket) and floor
    grid(m, (-x, -y, FLOOR), (2 * x, 0, 0), (0, 0, H - FLOOR), nx, nz, const((0, 1, 0)))
    grid(m, (x, -y, FLOOR), (0, 2 * y, 0), (0, 0, H - FLOOR), ny, nz, const((-1, 0, 0)))
    grid(m, (x, y, FLOOR), (-2 * x, 0, 0), (0, 0, H - FLOOR), nx, nz, const((0, -1, 0)))
    grid(m, (-x, y, FLOOR), (0, -2 * y, 0), (0, 0, H - FLOOR), ny, nz, const((1, 0, 0)))
    grid(m, (-x, -y, FLOOR), (2 * x, 0, 0), (0, 2 * y, 0), nx, ny, const((0, 0, 1)))
    return m


def fixture():
    m = Mesh()
    X, Y, H = 0.040, 0.030, 0.020
    nx, ny, nz = 32, 24, 8
    r_hole, r_entry, chamfer, depth = 0.0026, 0.0036, 0.001, 0.008
    plate_with_holes(m, -X, X, -Y, Y, nx, ny, r_entry, 0.0, const((0, 0, 1)))
    for cx in (PIN_X, -PIN_X):
        profile = [(lin(r_entry, r_hole, t), -chamfer * t) for t in (0.0, 0.25, 0.5, 0.75)]
        profile += [(r_hole, z) for z in steps(-chamfer, -depth, 10)]
        revolve(m, cx, profile, -1)
        disc(m, cx, r_hole, -depth, 4, +1)
    grid(m, (-X, -Y, -H), (2 * X, 0, 0), (0, 0, H), nx, nz, const((0, -1, 0)))
    grid(m, (X, -Y, -H), (0, 2 * Y, 0), (0, 0, H), ny, nz, const((1, 0, 0)))
    grid(m, (X, Y, -H), (-2 * X, 0, 0), (0, 0, H), nx, nz, const((0, 1, 0)))
    grid(m, (-X, Y, -H), (0, -2 * Y, 0), (0, 0, H), ny, nz, const((-1, 0, 0)))
    grid(m, (-X, -Y, -H), (2 * X, 0, 0), (0, 2 * Y, 0), nx, ny, const((0, 0, -1)))
    return m


if __name__ == "__main__":
    meshes = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "scenarios",
                          "meshes")
    for name, mesh in (("tray_10k.stl", tray()), ("fixture_10k.stl", fixture())):
        mesh.write_stl(os.path.join(meshes, name))
        print(f"{name}: {len(mesh.tris)} triangles, {len(mesh.points)} vertices")
