"""The command line itself (cli/): parser errors exit 2 with CLI11's message, and each
command's options are checked before any work."""

from case import Case


def cli(name, args, expect, outputs=(), pending=None, files=None, folders=()):
    return Case("cli/" + name, args, expect, outputs=outputs, pending=pending, files=files,
                folders=folders)


def tess(name, extra, expect, shape="sphere:0.01", pending=None):
    return cli("tessellate_" + name, ["tessellate", shape, "--out", "t.stl"] + extra, expect,
               outputs=["t.stl"], pending=pending)


def friction(name, extra, expect, pending=None):
    return cli("friction_map_" + name, ["friction-map", "--out", "f.csv"] + extra, expect,
               outputs=["f.csv"], pending=pending)


CASES = [
    cli("no_subcommand", [], ["subcommand"]),
    cli("unknown_subcommand", ["simulat", "x.json"], ["'simulat'", "simulate"]),
    cli("unknown_option", ["volume", "sphere:0.01", "halfspace", "--posea", "0,0,0"],
        ["--posea"]),
    cli("missing_positional", ["volume", "sphere:0.01"], ["B"]),
    cli("missing_required_option", ["compare", "rig.json", "--out", "out"], ["--model"],
        outputs=["out"]),
    cli("option_without_value", ["volume", "sphere:0.01", "halfspace", "--pose-a"],
        ["--pose-a"]),
    cli("extra_positional", ["mesh-info", "sphere:0.01", "sphere:0.02"], ["sphere:0.02"]),
    cli("method_unknown", ["volume", "sphere:0.01", "halfspace", "--method", "magic",
                           "--out", "v.json"], ["--method"], outputs=["v.json"]),
    cli("density_text", ["mesh-info", "sphere:0.01", "--density", "steel"], ["--density"]),
    cli("density_nan", ["mesh-info", "sphere:0.01", "--density", "nan"], ["--density"]),
    cli("density_absurd", ["mesh-info", "sphere:0.01", "--density", "1e300"],
        ["--density", "100000"]),
    cli("mesh_info_shape_nan", ["mesh-info", "sphere:nan", "--json"], []),
    cli("weld_tolerance_negative", ["mesh-repair", "c.stl", "--out", "r.obj",
                                    "--weld-tolerance", "-1"], ["--weld-tolerance"],
        outputs=["r.obj"]),
    cli("weld_tolerance_text", ["mesh-repair", "c.stl", "--out", "r.obj", "--weld-tolerance",
                                "big"], ["--weld-tolerance"], outputs=["r.obj"]),
    cli("mesh_repair_primitive", ["mesh-repair", "sphere:0.01", "--out", "r.obj"],
        ["sphere:0.01"], outputs=["r.obj"]),
    tess("segments_text", ["--segments", "many"], ["--segments"]),
    tess("segments_float", ["--segments", "1.5"], ["--segments"]),
    tess("segments_two", ["--segments", "2"], ["--segments"]),
    tess("segments_overflow", ["--segments", "99999999999"], ["--segments"]),
    tess("segments_and_rings_huge", ["--segments", "100000", "--rings", "100000"],
         ["--segments", "triangles"]),
    tess("rings_one", ["--rings", "1"], ["--rings"]),
    tess("halfspace", [], ["halfspace"], shape="halfspace"),
    tess("sphere_nan", [], ["sphere:nan", "not a number"], shape="sphere:nan"),
    tess("box_negative", [], ["box:1,1,-1"], shape="box:1,1,-1"),
    friction("radius_negative", ["--radius", "-0.01"], ["--radius"]),
    friction("radius_nan", ["--radius", "nan"], ["--radius"]),
    friction("load_text", ["--load", "heavy"], ["--load"]),
    friction("load_negative", ["--load", "-10"], ["--load"]),
    friction("mu_negative", ["--mu", "-0.1"], ["--mu"]),
    friction("kv_zero", ["--kv", "0"], ["--kv"]),
    friction("eps_range_reversed", ["--eps-min", "10", "--eps-max", "1"], ["--eps"]),
    friction("per_decade_zero", ["--per-decade", "0"], ["--per-decade"]),
    friction("speed_nan", ["--speed", "nan"], ["--speed"]),
    friction("shape_bad", ["--shape", "sphere:-1"], ["sphere:-1"]),
    friction("depth_negative", ["--depth", "-1"], ["--depth"]),
    cli("max_iterations_zero", ["fit", "rig.json", "--model", "m.json", "--out", "out",
                                "--max-iterations", "0"], ["--max-iterations"],
        outputs=["out"]),
    cli("loss_unknown", ["fit", "{assets}/datasets/impacts.json", "--model",
                         "{assets}/datasets/models/bare.model.json", "--out", "out", "--loss",
                         "square"], ["--loss"], outputs=["out"]),
    cli("out_is_a_file", ["compare", "{assets}/datasets/impacts.json", "--model",
                          "{assets}/datasets/models/impacts-truth.model.json", "--out",
                          "taken"], ["--out", "taken"], files={"taken": "x"}),
    cli("field_without_columns", ["volume", "sphere:0.01", "halfspace", "--pose-a",
                                  "0,0,0.005", "--method", "analytic", "--field", "f.csv"],
        ["--field"], outputs=["f.csv"]),
    cli("simulate_out_is_a_file", ["simulate", "{assets}/scenarios/ball_drop.json", "--out",
                                   "taken", "--quiet"], ["taken"], files={"taken": "x"}),
    # A command's files appear together or not at all (io::OutputSet): the last one cannot be
    # written, and none of those before it is left.
    cli("volume_json_to_dev_full", ["volume", "{assets}/meshes/ball_r10mm.stl", "halfspace",
                                    "--pose-a",
                                    "0,0,0.0095", "--method", "columns", "--field", "f.csv",
                                    "--out", "/dev/full"],
        ["/dev/full", "No space left on device"], outputs=["f.csv"]),
] + [
    cli("%s_report_path_is_a_folder" % command,
        [command, "{assets}/datasets/impacts.json", "--model",
         "{assets}/datasets/models/impacts-truth.model.json", "--out", "out", "--starts", "0",
         "--max-iterations", "1"][:6 if command == "compare" else 10],
        ["out/report.html", "is a folder"], folders=["out/report.html"],
        outputs=["out/" + f for f in files])
    for command, files in (("compare", ["residuals.csv", "compare.json"]),
                           ("fit", ["model.json", "fit.json", "residuals.csv"]),
                           ("diagnose", ["diagnosis.json", "model.json", "residuals.csv"]))
] + [
    # A folder no file can be created in, whoever runs the test (permission bits do not stop
    # root, /proc does): exit 2 naming the path, never "filesystem error" or exit 1.
    cli("tessellate_out_in_unwritable_folder",
        ["tessellate", "sphere:0.01", "--out", "/proc/vcontact-bad.stl"],
        ["/proc/vcontact-bad.stl", "cannot create a file in folder '/proc'"],
        outputs=["/proc/vcontact-bad.stl"]),
    cli("simulate_out_under_unwritable_folder",
        ["simulate", "{assets}/scenarios/ball_drop.json", "--out", "/proc/vcontact-bad/out",
         "--quiet"], ["/proc/vcontact-bad/out", "cannot create the output folder"]),
    cli("simulate_out_is_unwritable_folder",
        ["simulate", "{assets}/scenarios/ball_drop.json", "--out", "/proc", "--quiet"],
        ["/proc/", "cannot create a file in folder '/proc'"]),
    cli("compare_out_under_unwritable_folder",
        ["compare", "{assets}/datasets/impacts.json", "--model",
         "{assets}/datasets/models/impacts-truth.model.json", "--out", "/proc/vcontact-bad"],
        ["/proc/vcontact-bad", "cannot create the output folder"]),
    cli("synth_out_in_unwritable_folder",
        ["synth", "--profile", "impacts", "--model",
         "{assets}/datasets/models/impacts-truth.model.json", "--samples", "200", "--out",
         "/proc/vcontact-bad.json"],
        ["/proc/vcontact-bad.csv", "cannot create a file in folder '/proc'"],
        outputs=["/proc/vcontact-bad.csv", "/proc/vcontact-bad.json"]),
] + [
    # A full disk (/dev/full takes the open and fails every write): the write is checked.
    cli("%s_to_dev_full" % name, args + ["--out", "/dev/full"],
        ["/dev/full: write failed", "No space left on device"])
    for name, args in (("tessellate", ["tessellate", "sphere:0.01"]),
                       ("mesh_repair", ["mesh-repair", "{assets}/meshes/ball_r10mm.stl"]),
                       ("friction_map", ["friction-map"]))
] + [
    cli("synth_sidecar_is_a_folder", ["synth", "--profile", "impacts", "--model",
                                      "{assets}/datasets/models/impacts-truth.model.json",
                                      "--samples", "200", "--out", "d.json"],
        ["d.json", "is a folder"], folders=["d.json"], outputs=["d.csv"]),
]

# vcontact study (docs/STUDY.md): the study file is checked before a folder is made or a run
# starts. (Bad parameters, outputs and schedulers: python/tests/study, CTest python/study.)
def study(name, text, expect):
    return cli("study_" + name, ["study", "s.json", "--out", "o", "--workers", "0"], expect,
               outputs=["o"], files={"s.json": text})


CASES += [
    cli("study_missing", ["study", "nothing.json", "--out", "o"],
        ["nothing.json", "cannot read"], outputs=["o"]),
    study("not_json", "{", ["s.json", "line 1", "not JSON"]),
    study("unknown_key", '{"format": "vcontact.study/1", "runs": 3}',
          ["s.json", "runs", "unknown key"]),
    study("no_scenario", '{"format": "vcontact.study/1", "scenario": "none.json"}',
          ["s.json", "scenario", "none.json", "cannot read"]),
    cli("study_negative_workers", ["study", "s.json", "--out", "o", "--workers", "-1"],
        ["--workers"], outputs=["o"], files={"s.json": "{}"}),
]
