"""The binary STL writer shared by the scripts that generate the bundled meshes
(scripts/bin_parts.py, scripts/peg_hole_meshes.py, scripts/cad_parts.py).

Binary STL: an 80-byte header, a little-endian uint32 triangle count, then per triangle a
normal (written as zeros: vcontact and every reader we use recompute it from the winding),
three vertices as float32 and a uint16 attribute count of 0."""
import struct


def write_binary_stl(path, points, tris, header):
    """Writes triangles `tris` (index triples into `points`, counter-clockwise seen from
    outside) to `path`; `header` is the text of the 80-byte header (at most 80 ASCII bytes)."""
    text = header.encode("ascii")
    if len(text) > 80:
        raise ValueError(f"STL header longer than 80 bytes: {header!r}")
    with open(path, "wb") as f:
        f.write(text.ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            for i in t:
                f.write(struct.pack("<3f", *points[i]))
            f.write(struct.pack("<H", 0))
