#!/usr/bin/env python3
"""Writes the meshes of assets/scenarios/housing_drop.json and parts_bin.json as binary STL
files (metres):

  housing.stl   an injection-moulded / 3D-printed electronics housing, open at the bottom:
                outer 80 x 60 x 30 mm, 2.5 mm walls, a 3 mm top; two 1.5 mm ribs across the
                inside hanging 12 mm from the top; four 7 x 7 mm screw bosses in the corners
                reaching down to 1 mm above the rim, each with a 3 x 3 mm pilot hole 14 mm
                deep; a 12 x 6 mm cable notch in one long wall; a 16 x 10 mm connector window
                through the top. It rests on its rim (the bosses are 1 mm short of it).
  bracket.stl   an L-bracket 40 x 30 x 25 mm, 4 mm thick, with a 3 mm gusset rib and two
                6 x 6 mm slots through the base.
  plate.stl     a fixture plate 160 x 120 x 10 mm, its top face at z = 0.

Each part is a solid over a rectilinear grid of cells, the material of each cell spanning
bottom <= z <= top (or none): every face is axis-aligned, as a CAD part's prismatic features
are, and the grid's lines follow the features' edges (cells at most MAX_CELL mm, so that the
flat faces carry the several thousand triangles of an STL export). The vertical faces between two cells carry a vertex at
every height any cell meets at their corners, so there are no T-junctions; the script checks
that every edge is used once in each direction and that the volume equals the sum of the
cells' columns before writing, and prints each part's volume, triangle count and the area of
its footprint on a plane below it (the faces at its lowest z), which the tests' static sink
uses (tests/formats/housing_drop_test.cpp).
Run:  python3 scripts/housing_parts.py [OUT_DIR]   (default assets/scenarios/meshes/housing)
"""
import os
import sys

from stl_writer import write_binary_stl

MM = 1e-3
MAX_CELL = 2.5  # mm, the largest cell side


def breakpoints(lo, hi, edges, max_cell):
    """Sorted grid lines from lo to hi through every feature edge, no gap above max_cell."""
    cuts = sorted({lo, hi, *[e for e in edges if lo < e < hi]})
    out = [cuts[0]]
    for a, b in zip(cuts, cuts[1:]):
        n = max(1, int(-(-(b - a) // max_cell)))
        out.extend(a + (b - a) * k / n for k in range(1, n + 1))
    return out


class Part:
    """A solid over a rectilinear grid of cells (mm): in each cell the material spans
    bottom <= z <= top, or the cell is empty. Features set rectangles, later over earlier."""

    def __init__(self, max_cell=MAX_CELL):
        self.max_cell = max_cell
        self.features = []  # ((x0, x1, y0, y1), (bottom, top) or None)

    def set(self, x0, x1, y0, y1, bottom, top):
        self.features.append(((x0, x1, y0, y1), (bottom, top)))

    def cut(self, x0, x1, y0, y1):
        """No material over the rectangle (a hole through the part)."""
        self.features.append(((x0, x1, y0, y1), None))

    def column(self, x, y):
        col = None
        for (x0, x1, y0, y1), span in self.features:
            if x0 <= x <= x1 and y0 <= y <= y1:
                col = span
        return col

    def mesh(self):
        xs = breakpoints(min(r[0] for r, _ in self.features), max(r[1] for r, _ in self.features),
                         [e for (r, _) in self.features for e in r[:2]], self.max_cell)
        ys = breakpoints(min(r[2] for r, _ in self.features), max(r[3] for r, _ in self.features),
                         [e for (r, _) in self.features for e in r[2:]], self.max_cell)
        nx, ny = len(xs) - 1, len(ys) - 1
        # The span of cell (i, j) at col[i + 1][j + 1], padded with empty cells around.
        col = [[None] * (ny + 2) for _ in range(nx + 2)]
        for i in range(nx):
            for j in range(ny):
                col[i + 1][j + 1] = self.column((xs[i] + xs[i + 1]) / 2, (ys[j] + ys[j + 1]) / 2)
        points, index, tris = [], {}, []

        def v(i, j, z):
            if (i, j, z) not in index:
                index[(i, j, z)] = len(points)
                points.append((xs[i] * MM, ys[j] * MM, z * MM))
            return index[(i, j, z)]

        def heights_at(i, j):
            """Every height a face meets on the vertical line at grid vertex (i, j)."""
            return sorted({h for di in (0, 1) for dj in (0, 1) if col[i + di][j + dj]
                           for h in col[i + di][j + dj]})

        def wall(p, q, lo, hi):
            """Vertical polygon on grid edge p -> q between heights lo < hi, every height of
            the two vertex lines in between a vertex, as a strip of triangles between the two
            lines (each with an edge on one line and a corner on the other: none degenerate);
            its normal is p -> q turned clockwise seen from above."""
            left = [v(*p, h) for h in heights_at(*p) if lo <= h <= hi]
            right = [v(*q, h) for h in heights_at(*q) if lo <= h <= hi]
            zl = [h for h in heights_at(*p) if lo <= h <= hi]
            zr = [h for h in heights_at(*q) if lo <= h <= hi]
            i = j = 0
            while i < len(left) - 1 or j < len(right) - 1:
                if j < len(right) - 1 and (i == len(left) - 1 or zr[j + 1] <= zl[i + 1]):
                    tris.append((right[j], right[j + 1], left[i]))
                    j += 1
                else:
                    tris.append((right[j], left[i + 1], left[i]))
                    i += 1

        def exposed(mine, other):
            """The parts of span `mine` that span `other` does not cover."""
            if mine is None:
                return []
            if other is None:
                return [mine]
            out = []
            if mine[0] < other[0]:
                out.append((mine[0], min(mine[1], other[0])))
            if mine[1] > other[1]:
                out.append((max(mine[0], other[1]), mine[1]))
            return [s for s in out if s[1] > s[0]]

        for i in range(nx):
            for j in range(ny):
                span = col[i + 1][j + 1]
                if span is None:
                    continue
                lo, hi = span
                tris += [(v(i, j, lo), v(i + 1, j + 1, lo), v(i + 1, j, lo)),
                         (v(i, j, lo), v(i, j + 1, lo), v(i + 1, j + 1, lo)),   # facing down
                         (v(i, j, hi), v(i + 1, j, hi), v(i + 1, j + 1, hi)),
                         (v(i, j, hi), v(i + 1, j + 1, hi), v(i, j + 1, hi))]   # facing up
        # Walls on the grid lines x = xs[I] (cells I and I + 1 of the padded grid either side)
        # and y = ys[J]; a span exposed to its neighbour faces it.
        for I in range(nx + 1):
            for J in range(1, ny + 1):
                left, right = col[I][J], col[I + 1][J]
                p, q = (I, J - 1), (I, J)
                for lo, hi in exposed(left, right):   # faces +x
                    wall(p, q, lo, hi)
                for lo, hi in exposed(right, left):   # faces -x
                    wall(q, p, lo, hi)
        for J in range(ny + 1):
            for I in range(1, nx + 1):
                below, above = col[I][J], col[I][J + 1]
                p, q = (I - 1, J), (I, J)
                for lo, hi in exposed(below, above):  # faces +y
                    wall(q, p, lo, hi)
                for lo, hi in exposed(above, below):  # faces -y
                    wall(p, q, lo, hi)
        cells = [((xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]), col[i + 1][j + 1])
                 for i in range(nx) for j in range(ny) if col[i + 1][j + 1]]
        column_volume = sum(area * (span[1] - span[0]) for area, span in cells)
        low = min(span[0] for _, span in cells)
        footprint = sum(area for area, span in cells if span[0] == low)
        return points, tris, column_volume, footprint


def check_closed(name, points, tris, column_volume):
    directed = {}
    for t in tris:
        for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            directed[e] = directed.get(e, 0) + 1
    bad = [e for e, n in directed.items() if n != 1 or directed.get((e[1], e[0])) != 1]
    if bad:
        sys.exit(f"housing_parts.py: {name}: edge {bad[0]} is not shared by exactly two "
                 "opposite triangles (the solid is not closed)")
    vol = 0.0
    for a, b, c in tris:
        pa, pb, pc = points[a], points[b], points[c]
        vol += (pa[0] * (pb[1] * pc[2] - pb[2] * pc[1]) - pa[1] * (pb[0] * pc[2] - pb[2] * pc[0]) +
                pa[2] * (pb[0] * pc[1] - pb[1] * pc[0])) / 6.0
    if abs(vol / MM**3 - column_volume) > 1e-6 * column_volume:
        sys.exit(f"housing_parts.py: {name}: mesh volume {vol / MM**3} mm^3 is not the "
                 f"columns' {column_volume} mm^3 (a face is missing or turned)")


def housing():
    """Origin at the middle of the rim's plane (the open bottom at z = 0)."""
    p = Part()
    p.set(-40, 40, -30, 30, 0, 30)                  # the walls, 2.5 mm ...
    p.set(-37.5, 37.5, -27.5, 27.5, 27, 30)         # ... round a cavity under the 3 mm top
    for y in (-9.75, 8.25):                         # two ribs across, 1.5 mm, 12 mm deep
        p.set(-37.5, 37.5, y, y + 1.5, 15, 30)
    for sx in (-1, 1):                              # four bosses in the corners, to 1 mm
        for sy in (-1, 1):                          # above the rim, each with a pilot hole
            bx, by = sx * 31.5, sy * 21.5           # 14 mm deep
            p.set(bx - 3.5, bx + 3.5, by - 3.5, by + 3.5, 1, 30)
            p.set(bx - 1.5, bx + 1.5, by - 1.5, by + 1.5, 15, 30)
    p.set(-6, 6, -30, -27.5, 6, 30)                 # cable notch in the -y wall, 6 mm high
    p.cut(-14, 2, 2, 8.25)                          # connector window through the top
    return p


def bracket():
    """An L-bracket: a 40 x 30 x 4 mm base on z = 0, a 4 mm upright along -y to z = 25, a
    3 mm rib joining them in the middle, two 6 x 6 mm slots through the base."""
    p = Part()
    p.set(-20, 20, -15, 15, 0, 4)
    p.set(-20, 20, -15, -11, 0, 25)
    p.set(-1.5, 1.5, -11, 3, 0, 14)
    for x in (-12, 12):
        p.cut(x - 3, x + 3, 0, 6)
    return p


def plate():
    """A fixture plate 160 x 120 x 10 mm, its top face at z = 0 (coarse: 20 mm cells)."""
    p = Part(max_cell=20)
    p.set(-80, 80, -60, 60, -10, 0)
    return p


PARTS = {"housing": housing, "bracket": bracket, "plate": plate}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "assets", "scenarios", "meshes", "housing")
    os.makedirs(out, exist_ok=True)
    for name, make in PARTS.items():
        points, tris, column_volume, footprint = make().mesh()
        check_closed(name, points, tris, column_volume)
        write_binary_stl(os.path.join(out, f"{name}.stl"), points, tris,
                         "vcontact scripts/housing_parts.py")
        print(f"{name}.stl: {len(tris)} triangles, {column_volume:.3f} mm^3, "
              f"footprint {footprint:.3f} mm^2")


if __name__ == "__main__":
    main()
