"""Mesh files (io/mesh_io): broken files, NaN and infinite coordinates, overlapping shells,
absurd sizes, paths and scales."""

import math
import struct

from case import Case

# A unit cube, outward-facing triangles (corner indices into CUBE_POINTS).
CUBE_POINTS = [(x, y, z) for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)]
CUBE_FACES = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
              (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]


def cube_triangles(offset=(0.0, 0.0, 0.0), size=1.0):
    return [[tuple(o + size * c for o, c in zip(offset, CUBE_POINTS[i])) for i in f]
            for f in CUBE_FACES]


def stl_binary(triangles):
    out = bytearray(b"binary cube".ljust(80, b" "))
    out += struct.pack("<I", len(triangles))
    for t in triangles:
        out += struct.pack("<3f", 0.0, 0.0, 0.0)
        for p in t:
            out += struct.pack("<3f", *p)
        out += struct.pack("<H", 0)
    return bytes(out)


def stl_ascii(triangles, number=repr):
    lines = ["solid cube"]
    for t in triangles:
        lines += ["facet normal 0 0 0", "outer loop"]
        lines += ["vertex %s %s %s" % tuple(number(c) for c in p) for p in t]
        lines += ["endloop", "endfacet"]
    return "\n".join(lines + ["endsolid cube", ""])


def obj(triangles):
    points, lines = [], []
    for t in triangles:
        for p in t:
            points.append(p)
            lines.append("v %r %r %r" % p)
    n = 0
    for t in triangles:
        lines.append("f %d %d %d" % (n + 1, n + 2, n + 3))
        n += 3
    return "\n".join(lines) + "\n"


def off(points=CUBE_POINTS, faces=CUBE_FACES, header=None):
    head = header or "OFF\n%d %d 0" % (len(points), len(faces))
    return "\n".join([head] + ["%r %r %r" % p for p in points] +
                     ["3 %d %d %d" % f for f in faces]) + "\n"


def ply(points=CUBE_POINTS, faces=CUBE_FACES, vertex_count=None, end_header=True):
    head = ["ply", "format ascii 1.0", "element vertex %d" % (vertex_count or len(points)),
            "property double x", "property double y", "property double z",
            "element face %d" % len(faces), "property list uchar int vertex_indices"]
    if end_header:
        head.append("end_header")
    return "\n".join(head + ["%r %r %r" % p for p in points] +
                     ["3 %d %d %d" % f for f in faces]) + "\n"


def with_value(triangles, t, corner, axis, value):
    out = [list(p) for p in triangles[t]]
    out[corner][axis] = value
    changed = list(triangles)
    changed[t] = [tuple(p) for p in out]
    return changed


def info(name, filename, content, expect, pending=None, code=2):
    return Case("mesh/" + name, ["mesh-info", filename], [filename] + expect,
                files={filename: content}, code=code, pending=pending)


def repair(name, filename, content, expect, pending=None):
    return Case("mesh/repair_" + name, ["mesh-repair", filename, "--out", "fixed.obj"],
                [filename] + expect, files={filename: content}, outputs=["fixed.obj"],
                pending=pending)


CUBE = cube_triangles()
NAN_CASES = []
# A NaN in each of the 12 triangles, at a changing corner and axis: binary STL repeats every
# corner, so each one must be found before vertices are welded (issue 20).
for t in range(12):
    corner, axis = t % 3, (t // 3) % 3
    NAN_CASES.append(info("stl_binary_nan_t%d_c%d_a%d" % (t, corner, axis), "cube.stl",
                          stl_binary(with_value(CUBE, t, corner, axis, math.nan)),
                          ["NaN or infinite coordinate", "vertex"]))
for t, value in ((0, math.inf), (5, -math.inf), (11, math.inf)):
    NAN_CASES.append(info("stl_binary_inf_t%d" % t, "cube.stl",
                          stl_binary(with_value(CUBE, t, 1, 2, value)),
                          ["NaN or infinite coordinate"]))

OPEN_BOX = CUBE[:-2]
OVERLAPPING = cube_triangles() + cube_triangles(offset=(0.5, 0.0, 0.0))
NESTED = cube_triangles() + cube_triangles(offset=(0.25, 0.25, 0.25), size=0.5)
HUGE = [[tuple(1e300 * c for c in p) for p in t] for t in CUBE]
TINY = [[tuple(1e-300 * c for c in p) for p in t] for t in CUBE]

CASES = NAN_CASES + [
    info("stl_ascii_nan", "cube.stl", stl_ascii(with_value(CUBE, 3, 0, 0, math.nan)),
         ["NaN or infinite coordinate"]),
    info("obj_nan", "cube.obj", obj(with_value(CUBE, 7, 2, 1, math.nan)),
         ["NaN or infinite coordinate"]),
    info("off_inf", "cube.off", off(points=[(math.inf, 0.0, 0.0)] + CUBE_POINTS[1:]),
         ["NaN or infinite coordinate", "line 3"]),
    info("ply_nan", "cube.ply", ply(points=CUBE_POINTS[:3] + [(0.0, math.nan, 1.0)] +
                                    CUBE_POINTS[4:]), ["NaN or infinite coordinate"]),
    info("stl_empty", "cube.stl", b"", ["no triangles"]),
    info("obj_empty", "cube.obj", "", ["cannot read"]),
    info("off_empty", "cube.off", "", ["cannot read"]),
    info("ply_empty", "cube.ply", "", ["cannot read"]),
    info("stl_garbage", "cube.stl", bytes(range(256)) * 3, ["cannot read"]),
    info("stl_binary_truncated", "cube.stl", stl_binary(CUBE)[:300], ["cannot read"]),
    info("stl_binary_count_too_large", "cube.stl",
         stl_binary(CUBE)[:80] + struct.pack("<I", 10**9) + stl_binary(CUBE)[84:],
         ["cannot read"]),
    info("stl_ascii_truncated", "cube.stl", stl_ascii(CUBE)[:500], ["cannot read"]),
    info("stl_ascii_word_for_number", "cube.stl",
         stl_ascii(CUBE).replace("vertex 0.0", "vertex zero", 1), ["cannot read"]),
    # CGAL's OBJ and OFF readers refuse a face beyond the vertices without saying where.
    info("obj_index_beyond", "cube.obj", obj(CUBE) + "f 1 2 99\n", ["not a valid obj file"]),
    info("obj_only_points", "cube.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", ["cannot read"]),
    info("off_counts_too_large", "cube.off", off(header="OFF\n80 12 0"), ["cannot read"]),
    info("off_face_beyond", "cube.off", off(faces=CUBE_FACES[:-1] + [(1, 7, 30)]),
         ["not a valid off file"]),
    info("ply_header_never_ends", "cube.ply", ply(end_header=False), ["cannot read"]),
    info("ply_header_only", "cube.ply",
         "ply\nformat ascii 1.0\n" + "comment padding\n" * 20000, ["cannot read"]),
    info("ply_fewer_vertices", "cube.ply", ply(vertex_count=20), ["cannot read"]),
    info("ply_binary_truncated", "cube.ply",
         b"ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\n"
         b"property float y\nproperty float z\nelement face 12\n"
         b"property list uchar int vertex_indices\nend_header\n" + b"\x00" * 40,
         ["cannot read"]),
    # Found by tests/fuzz (mesh_reader_fuzz): a property line before any element line made
    # CGAL's PLY reader take the last element of an empty list (undefined behaviour).
    info("ply_property_before_element", "cube.ply",
         "ply\nformat ascii 1.0\nproperty double x\nelement vertex 1\nend_header\n0\n",
         ["PLY header line 3", "a property before any element"]),
    info("ply_not_ply", "cube.ply", "solid cube\n", ["line 1", "expected a PLY file"]),
    info("ply_unknown_format", "cube.ply", ply().replace("ascii 1.0", "base64 1.0"),
         ["cannot read"]),
    info("gltf_not_json", "cube.gltf", "{ not json", ["cannot read"]),
    info("unknown_extension", "cube.xyz", "0 0 0\n1 1 1\n", ["cannot read"]),
    info("open_box", "cube.obj", obj(OPEN_BOX), ["boundary edge"]),
    info("overlapping_shells", "cubes.obj", obj(OVERLAPPING), ["shells", "intersect"]),
    info("nested_shells_same_orientation", "cubes.obj", obj(NESTED), ["inside another"]),
    info("huge_coordinates", "cube.stl", stl_ascii(HUGE), ["1000"]),
    info("tiny_coordinates", "cube.stl", stl_ascii(TINY), ["1e-06"]),
    info("flat", "flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n", []),
    Case("mesh/no_such_file", ["mesh-info", "missing.stl"], ["missing.stl", "no such file"]),
    Case("mesh/folder_as_file", ["mesh-info", "part.stl"], ["part.stl", "folder"],
         folders=["part.stl"]),
    Case("mesh/scale_zero", ["mesh-info", "cube.stl@0"], ["cube.stl", "scale"],
         files={"cube.stl": stl_binary(CUBE)}),
    Case("mesh/scale_negative", ["mesh-info", "cube.stl@-1"], ["cube.stl", "scale"],
         files={"cube.stl": stl_binary(CUBE)}),
    Case("mesh/scale_huge", ["mesh-info", "cube.stl@1e300"], ["cube.stl", "1000"],
         files={"cube.stl": stl_binary(CUBE)}),
    Case("mesh/scale_nan", ["mesh-info", "cube.stl@nan"], ["cube.stl@nan", "no such file"],
         files={"cube.stl": stl_binary(CUBE)}),
    Case("mesh/scale_unknown_unit", ["mesh-info", "cube.stl@km"],
         ["cube.stl@km", "no such file"], files={"cube.stl": stl_binary(CUBE)}),
    repair("nan", "cube.stl", stl_binary(with_value(CUBE, 4, 1, 0, math.nan)),
           ["NaN or infinite coordinate"]),
    repair("garbage", "cube.stl", b"\x01\x02" * 100, ["cannot read"]),
    repair("overlapping_shells", "cubes.obj", obj(OVERLAPPING), ["intersect"]),
    # A path with '@' that exists is a path (false rejection in issue 20): these must pass.
    Case("mesh/at_in_folder_is_a_path", ["mesh-info", "a@b/cube.stl"], [],
         files={"a@b/cube.stl": stl_binary(CUBE)}, code=0),
    Case("mesh/at_unit_like_folder_is_a_path", ["mesh-info", "b@mm/cube.stl@mm"], [],
         files={"b@mm/cube.stl": stl_binary(cube_triangles(size=1000.0))}, code=0),
    Case("mesh/disjoint_shells_accepted", ["mesh-info", "two.obj"], [],
         files={"two.obj": obj(cube_triangles() + cube_triangles(offset=(2.0, 0.0, 0.0)))},
         code=0),
]
