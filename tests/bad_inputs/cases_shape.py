"""Shapes and poses typed on the command line (io/shape_spec, formats/input_ranges.hpp)."""

from case import Case

OUT = "volume.json"


def volume(name, a, b="halfspace", pose_a="0,0,0", pose_b="0,0,0", expect=(), pending=None):
    return Case("shape/" + name,
                ["volume", a, b, "--pose-a", pose_a, "--pose-b", pose_b, "--out", OUT],
                expect, outputs=[OUT], pending=pending)


# (name, shape text, fragments): the shape is body A; its source reads "A (text)".
BAD_SHAPES = [
    ("sphere_zero", "sphere:0", ["A (sphere:0)", "radius"]),
    ("sphere_negative", "sphere:-0.01", ["A (sphere:-0.01)", "radius"]),
    ("sphere_nan", "sphere:nan", ["A (sphere:nan)", "not a number"]),
    ("sphere_inf", "sphere:inf", ["A (sphere:inf)", "not a number"]),
    ("sphere_tiny", "sphere:1e-300", ["A (sphere:1e-300)", "1e-06"]),
    ("sphere_huge", "sphere:1e300", ["A (sphere:1e300)", "1000"]),
    ("sphere_beyond_range", "sphere:1e4", ["A (sphere:1e4)", "1000"]),
    ("sphere_below_range", "sphere:1e-7", ["A (sphere:1e-7)", "1e-06"]),
    ("sphere_hex", "sphere:0x1p-4", ["A (sphere:0x1p-4)", "not a number"]),
    ("sphere_trailing_garbage", "sphere:0.01m", ["A (sphere:0.01m)", "not a number"]),
    ("sphere_trailing_comma", "sphere:0.01,", ["A (sphere:0.01,)", "not a number"]),
    ("sphere_two_numbers", "sphere:0.01,0.02", ["A (sphere:0.01,0.02)", "sphere:R"]),
    ("sphere_empty", "sphere:", ["A (sphere:)", "sphere:R"]),
    ("sphere_space_inside", "sphere:0. 01", ["A (sphere:0. 01)", "not a number"]),
    ("sphere_decimal_comma", "sphere:0,01", ["A (sphere:0,01)", "sphere:R"]),
    ("sphere_overflow", "sphere:1e400", ["A (sphere:1e400)", "range of a double"]),
    ("sphere_plus_plus", "sphere:++1", ["A (sphere:++1)", "not a number"]),
    ("cylinder_one_number", "cylinder:0.01", ["A (cylinder:0.01)", "cylinder:R,L"]),
    ("cylinder_zero_length", "cylinder:0.01,0", ["A (cylinder:0.01,0)", "length"]),
    ("cylinder_negative_radius", "cylinder:-1,1", ["A (cylinder:-1,1)", "radius"]),
    ("cylinder_huge_length", "cylinder:0.01,5e3", ["A (cylinder:0.01,5e3)", "1000"]),
    ("cylinder_empty_item", "cylinder:0.01,,0.02", ["A (cylinder:0.01,,0.02)", "not a number"]),
    ("box_two_numbers", "box:1,2", ["A (box:1,2)", "box:X,Y,Z"]),
    ("box_negative_edge", "box:0.1,0.1,-0.1", ["A (box:0.1,0.1,-0.1)", "box"]),
    ("box_nan_edge", "box:0.1,nan,0.1", ["A (box:0.1,nan,0.1)", "not a number"]),
    ("box_tiny_edge", "box:0.1,1e-9,0.1", ["A (box:0.1,1e-9,0.1)", "1e-06"]),
    ("halfspace_with_numbers", "halfspace:1", ["halfspace:1", "no such file"]),
    ("unknown_kind", "cone:1,2", ["cone:1,2", "no such file"]),
    ("empty_text", "", ["A ()", "empty text"]),
]

# (name, pose text, fragments): the pose of A.
BAD_POSES = [
    ("two_numbers", "1,2", ["--pose-a", "x,y,z"]),
    ("four_numbers", "0,0,0,1", ["--pose-a", "got 4 numbers"]),
    ("eight_numbers", "0,0,0,1,0,0,0,0", ["--pose-a", "got 8 numbers"]),
    ("trailing_comma", "0,0,0,", ["--pose-a", "not a number"]),
    ("leading_comma", ",0,0,0", ["--pose-a", "not a number"]),
    ("hex", "0x10,0,0", ["--pose-a", "not a number"]),
    ("hex_float", "0x1p3,0,0", ["--pose-a", "not a number"]),
    ("trailing_garbage", "0,0,0.5mm", ["--pose-a", "not a number"]),
    ("nan", "nan,0,0", ["--pose-a", "not a number"]),
    ("infinity", "0,-inf,0", ["--pose-a", "not a number"]),
    ("overflow", "0,0,1e400", ["--pose-a", "range of a double"]),
    ("far_away", "0,0,5000", ["--pose-a", "1000"]),
    ("far_negative", "-1e6,0,0", ["--pose-a", "1000"]),
    ("angle_beyond_360", "0,0,0,400,0,0", ["--pose-a", "360"]),
    ("angle_negative_beyond", "0,0,0,0,-720,0", ["--pose-a", "360"]),
    ("angle_nan", "0,0,0,0,0,nan", ["--pose-a", "not a number"]),
    ("quaternion_not_unit", "0,0,0,2,0,0,0", ["--pose-a", "unit length"]),
    ("quaternion_zero", "0,0,0,0,0,0,0", ["--pose-a", "unit length"]),
    ("quaternion_nan", "0,0,0,nan,0,0,0", ["--pose-a", "not a number"]),
    ("words", "up", ["--pose-a", "not a number"]),
    ("semicolons", "0;0;0", ["--pose-a", "not a number"]),
    ("empty", "", ["--pose-a", "not a number"]),
]

CASES = ([volume(n, text, expect=f) for n, text, f in BAD_SHAPES] +
         [volume("pose_" + n, "sphere:0.01", pose_a=text, expect=f) for n, text, f in BAD_POSES] +
         [volume("pose_b_far", "sphere:0.01", pose_b="0,1e9,0", expect=["--pose-b", "1000"]),
          volume("b_sphere_nan", "sphere:0.01", b="sphere:nan", expect=["B (sphere:nan)"])])
