#!/usr/bin/env python3
"""Writes the meshes of assets/scenarios/bin_of_ten.json as binary STL files (metres):

  bin.stl            an open-top box, inner 120 x 80 mm, 40 mm deep, 5 mm walls and floor,
                     the floor's top face at z = 0 (a closed solid, 28 triangles);
  part_<name>.stl    ten CAD-like parts of about 2,000 triangles each (see PARTS below):
                     solids of revolution (ball, roller, capsule, cone frustum, stepped
                     shaft, washer, torus), a rounded block (a superellipsoid), a bored
                     block and a hex nut (prisms with a round bore).

Every mesh is closed and consistently oriented by construction (each solid is one grid of
quads between rings of points that share their vertices); the script checks that every
edge is used once in each direction and that the signed volume is positive before writing.
Run:  python3 scripts/bin_parts.py [OUT_DIR]   (default assets/scenarios/meshes/bin)
"""
import math
import os
import sys

from stl_writer import write_binary_stl

MM = 1e-3


class Solid:
    """An indexed triangle mesh built from rings of vertices."""

    def __init__(self):
        self.points = []
        self.tris = []

    def add(self, p):
        self.points.append(tuple(float(c) for c in p))
        return len(self.points) - 1

    def ring(self, pts):
        return [self.add(p) for p in pts]

    def band(self, lower, upper):
        """Quads between two closed rings of equal length (or a ring and a pole: an int)."""
        n = len(lower) if isinstance(lower, list) else len(upper)
        for k in range(n):
            k1 = (k + 1) % n
            if isinstance(lower, int):
                self.tris.append((lower, upper[k1], upper[k]))
            elif isinstance(upper, int):
                self.tris.append((lower[k], lower[k1], upper))
            else:
                self.tris.append((lower[k], lower[k1], upper[k1]))
                self.tris.append((lower[k], upper[k1], upper[k]))

    def signed_volume(self):
        v = 0.0
        for a, b, c in self.tris:
            pa, pb, pc = self.points[a], self.points[b], self.points[c]
            v += (pa[0] * (pb[1] * pc[2] - pb[2] * pc[1]) - pa[1] * (pb[0] * pc[2] - pb[2] * pc[0]) +
                  pa[2] * (pb[0] * pc[1] - pb[1] * pc[0])) / 6.0
        return v

    def finish(self, name):
        """Orients the solid outward and checks that it is closed and manifold."""
        if self.signed_volume() < 0:
            self.tris = [(a, c, b) for a, b, c in self.tris]
        directed = {}
        for t in self.tris:
            for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
                directed[e] = directed.get(e, 0) + 1
        bad = [e for e, n in directed.items() if n != 1 or directed.get((e[1], e[0])) != 1]
        if bad:
            sys.exit(f"bin_parts.py: {name}: edge {bad[0]} is not shared by exactly two "
                     "opposite triangles (the solid is not closed)")
        return self

    def write_stl(self, path):
        write_binary_stl(path, self.points, self.tris, "vcontact scripts/bin_parts.py")


def revolve(profile, segments):
    """Solid of revolution about z of a profile of (r, z) points in mm. An open profile starts
    and ends on the axis (r = 0: poles); a profile whose points all have r > 0 is closed."""
    s = Solid()
    ang = [2 * math.pi * k / segments for k in range(segments)]
    rows = []
    for r, z in profile:
        if r == 0:
            rows.append(s.add((0, 0, z * MM)))
        else:
            rows.append(s.ring([(r * MM * math.cos(a), r * MM * math.sin(a), z * MM) for a in ang]))
    closed = all(r > 0 for r, _ in profile)
    for i in range(len(rows) - 1 + (1 if closed else 0)):
        s.band(rows[i], rows[(i + 1) % len(rows)])
    return s


def arc(cr, cz, radius, a0, a1, n):
    """n + 1 profile points on a circle about (cr, cz) from angle a0 to a1 (degrees)."""
    pts = []
    for i in range(n + 1):
        a = math.radians(a0 + (a1 - a0) * i / n)
        r = cr + radius * math.cos(a)
        pts.append((r if r > 1e-9 else 0.0, cz + radius * math.sin(a)))  # on the axis: a pole
    return pts


def lerp_pts(p, q, n):
    """Points from p to q (n intervals, both ends included)."""
    return [(p[0] + (q[0] - p[0]) * i / n, p[1] + (q[1] - p[1]) * i / n) for i in range(n + 1)]


def join(*parts):
    """Concatenates polylines, dropping each one's first point where it repeats the last."""
    out = []
    for p in parts:
        out.extend(p[1:] if out and p and out[-1] == p[0] else p)
    return out


def rounded_block(a, b, c, e, nu, nv):
    """A superellipsoid |x/a|^(2/e) + |y/b|^(2/e) + |z/c|^(2/e) <= 1 in mm (e < 1: a block
    with rounded edges), as rings of constant latitude between two poles."""
    def f(w, m):
        return math.copysign(abs(w) ** m, w)
    s = Solid()
    rows = [s.add((0, 0, -c * MM))]
    for j in range(1, nv):
        v = -math.pi / 2 + math.pi * j / nv
        ring = []
        for k in range(nu):
            u = 2 * math.pi * k / nu
            ring.append((a * MM * f(math.cos(v), e) * f(math.cos(u), e),
                         b * MM * f(math.cos(v), e) * f(math.sin(u), e), c * MM * f(math.sin(v), e)))
        rows.append(s.ring(ring))
    rows.append(s.add((0, 0, c * MM)))
    for i in range(len(rows) - 1):
        s.band(rows[i], rows[i + 1])
    return s


def bored_prism(outer_radius_at, bore, height, segments, layers):
    """A prism of height `height` (mm, z from -height/2) whose outline, seen from its axis at
    angle t, lies at outer_radius_at(t), with a round bore of radius `bore` through it."""
    s = Solid()
    ang = [2 * math.pi * k / segments for k in range(segments)]
    zs = [-height / 2 + height * i / layers for i in range(layers + 1)]
    outer = [s.ring([(outer_radius_at(a) * MM * math.cos(a), outer_radius_at(a) * MM * math.sin(a),
                      z * MM) for a in ang]) for z in zs]
    inner = [s.ring([(bore * MM * math.cos(a), bore * MM * math.sin(a), z * MM) for a in ang])
             for z in zs]
    loop = outer + inner[::-1]  # up the outside, down the bore; the caps join them
    for i in range(len(loop)):
        s.band(loop[i], loop[(i + 1) % len(loop)])
    return s


def polygon_radius(sides, apothem, turn=0.0):
    """Distance from the centre to a regular polygon's boundary at angle t (radians)."""
    sector = 2 * math.pi / sides
    return lambda t: apothem / math.cos(((t - turn) % sector) - sector / 2)


def block_radius(half_x, half_y):
    return lambda t: min(half_x / max(abs(math.cos(t)), 1e-12), half_y / max(abs(math.sin(t)), 1e-12))


def bin_solid():
    """Open-top box: outer 130 x 90 x 45 mm from z = -5 mm, inner pocket 120 x 80 from z = 0."""
    s = Solid()
    ox, oy, ix, iy = 65, 45, 60, 40

    def rect(hx, hy, z):
        return s.ring([(-hx * MM, -hy * MM, z * MM), (hx * MM, -hy * MM, z * MM),
                       (hx * MM, hy * MM, z * MM), (-hx * MM, hy * MM, z * MM)])
    bottom = s.add((0, 0, -5 * MM))
    floor = s.add((0, 0, 0))
    loop = [rect(ox, oy, -5), rect(ox, oy, 40), rect(ix, iy, 40), rect(ix, iy, 0)]
    s.band(bottom, loop[0])
    for i in range(3):
        s.band(loop[i], loop[i + 1])
    s.band(loop[3], floor)
    return s


# name -> solid; segment counts chosen for about 2,000 triangles each.
PARTS = {
    "ball": lambda: revolve(join([(0, -10)], arc(0, 0, 10, -90, 90, 24)[1:-1], [(0, 10)]), 42),
    "roller": lambda: revolve(join(lerp_pts((0, -15), (8, -15), 4), lerp_pts((8, -15), (8, 15), 16),
                                   lerp_pts((8, 15), (0, 15), 4)), 40),
    "capsule": lambda: revolve(join(arc(0, -9, 7, -90, 0, 10), arc(0, 9, 7, 0, 90, 10)), 48),
    "frustum": lambda: revolve(join(lerp_pts((0, -9), (11, -9), 6), lerp_pts((11, -9), (5, 9), 12),
                                    lerp_pts((5, 9), (0, 9), 4)), 44),
    "shaft": lambda: revolve(join(lerp_pts((0, -16), (6, -16), 3), lerp_pts((6, -16), (6, 4), 8),
                                  lerp_pts((6, 4), (11, 4), 3), lerp_pts((11, 4), (11, 14), 4),
                                  lerp_pts((11, 14), (0, 14), 5)), 44),
    "washer": lambda: revolve(join(lerp_pts((7, -2.5), (15, -2.5), 6), lerp_pts((15, -2.5), (15, 2.5), 3),
                                   lerp_pts((15, 2.5), (7, 2.5), 6), lerp_pts((7, 2.5), (7, -2.5), 3)[:-1]),
                              56),
    "torus": lambda: revolve(arc(12, 0, 4, 0, 360, 24)[:-1], 42),
    "rounded_block": lambda: rounded_block(15, 10, 7, 0.25, 48, 22),
    "bored_block": lambda: bored_prism(block_radius(14, 11), 6, 14, 96, 4),
    "hex_nut": lambda: bored_prism(polygon_radius(6, 12), 6.5, 10, 96, 4),
}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "assets", "scenarios", "meshes", "bin")
    os.makedirs(out, exist_ok=True)
    bin_solid().finish("bin").write_stl(os.path.join(out, "bin.stl"))
    for name, make in PARTS.items():
        solid = make().finish(name)
        solid.write_stl(os.path.join(out, f"part_{name}.stl"))
        print(f"part_{name}.stl: {len(solid.tris)} triangles, "
              f"{solid.signed_volume() * 1e9:.0f} mm^3")


if __name__ == "__main__":
    main()
