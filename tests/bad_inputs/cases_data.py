"""Rig datasets (formats/dataset_file), model files (formats/model_file) and the compare, fit,
diagnose and synth commands."""

import json

from case import Case, read_asset

# The impacts record, cut to its first ROWS samples: enough for every command, quick to read.
ROWS = 200
TRUTH = "datasets/models/impacts-truth.model.json"


def impacts(assets):
    sidecar = json.loads(read_asset(assets, "datasets/impacts.json"))
    lines = read_asset(assets, "datasets/impacts.csv").splitlines()[:ROWS + 1]
    return sidecar, lines


def cell(lines, row, column, value):
    """Line `row` of the CSV (1 = first sample) with `column` set to the text `value`."""
    names = lines[0].split(",")
    fields = lines[row].split(",")
    fields[names.index(column)] = value
    out = list(lines)
    out[row] = ",".join(fields)
    return out


def dataset_case(name, expect, sidecar=None, csv=None, command="compare", model=None,
                 pending=None, code=2):
    """sidecar(dict) and csv(list of lines) edit the record; model is a model file's text."""

    def files(assets):
        s, lines = impacts(assets)
        if sidecar:
            edited = sidecar(s)  # edits in place, or returns the sidecar's text
            s = s if edited is None else edited
        if csv:
            lines = csv(lines)
        text = s if isinstance(s, str) else json.dumps(s, indent=1)
        csv_text = lines if isinstance(lines, (str, bytes)) else "\n".join(lines) + "\n"
        return {"rig.json": text, "impacts.csv": csv_text,
                "model.json": model if model is not None else read_asset(assets, TRUTH)}

    return Case("dataset/%s_%s" % (command, name),
                [command, "rig.json", "--model", "model.json", "--out", "out"], expect,
                files=files, outputs=["out"], pending=pending, code=code)


def model_case(name, model, expect, command="compare"):
    text = model if isinstance(model, str) else json.dumps(model)
    return dataset_case("model_" + name, ["model.json"] + expect, command=command, model=text)


def effects(**e):
    return {"format": "vcontact.model/1", "effects": e}


DATASET_CASES = []
# The crashes of issue 20, for every command that reads a record.
for command in ("compare", "fit", "diagnose"):
    DATASET_CASES += [
        dataset_case("x_1e308", ["impacts.csv", "line 3", "'x'", "1000"], command=command,
                     csv=lambda l: cell(l, 2, "x", "1e308")),
        dataset_case("dt_1e-310", ["impacts.csv", "line 3", "'t'"], command=command,
                     csv=lambda l: cell(cell(l, 1, "t", "0"), 2, "t", "1e-310")),
        dataset_case("force_1e300", ["impacts.csv", "line 4", "'fz'"], command=command,
                     csv=lambda l: cell(l, 3, "fz", "1e300")),
    ]

DATASET_CASES += [
    dataset_case("nan_in_z", ["impacts.csv", "line 5", "'z'", "not"],
                 csv=lambda l: cell(l, 4, "z", "nan")),
    dataset_case("inf_in_fz", ["impacts.csv", "line 6", "'fz'", "not"],
                 csv=lambda l: cell(l, 5, "fz", "inf")),
    dataset_case("overflow_in_t", ["impacts.csv", "line 7", "'t'"],
                 csv=lambda l: cell(l, 6, "t", "1e400")),
    dataset_case("hex_in_x", ["impacts.csv", "line 3", "'x'", "not a number"],
                 csv=lambda l: cell(l, 2, "x", "0x10")),
    dataset_case("word_in_z", ["impacts.csv", "line 3", "'z'", "not a number"],
                 csv=lambda l: cell(l, 2, "z", "high")),
    dataset_case("empty_field", ["impacts.csv", "line 4", "'qw'", "not a number"],
                 csv=lambda l: cell(l, 3, "qw", "")),
    dataset_case("time_backwards", ["impacts.csv", "line 4", "'t'", "increase"],
                 csv=lambda l: cell(l, 3, "t", "0")),
    dataset_case("time_negative_far", ["impacts.csv", "line 2", "'t'"],
                 csv=lambda l: cell(l, 1, "t", "-1e12")),
    dataset_case("quaternion_zero", ["impacts.csv", "line 3", "quaternion"],
                 csv=lambda l: cell(l, 2, "qw", "0")),
    dataset_case("velocity_absurd", ["impacts.csv", "line 3", "'vz'"],
                 csv=lambda l: cell(l, 2, "vz", "1e200")),
    dataset_case("angular_velocity_absurd", ["impacts.csv", "line 3", "'wx'"],
                 csv=lambda l: cell(l, 2, "wx", "1e200")),
    dataset_case("utf8_bom", ["impacts.csv", "line 1", "byte order mark"],
                 csv=lambda l: "\ufeff" + "\n".join(l) + "\n"),
    dataset_case("decimal_commas", ["impacts.csv", "decimal comma"],
                 csv=lambda l: [l[0].replace(",", ";")] +
                 [r.replace(",", ";").replace(".", ",") for r in l[1:]]),
    dataset_case("semicolons", ["impacts.csv", "line 1"],
                 csv=lambda l: [r.replace(",", ";") for r in l]),
    dataset_case("short_row", ["impacts.csv", "line 3", "fields"],
                 csv=lambda l: l[:2] + [l[2].rsplit(",", 1)[0]] + l[3:]),
    dataset_case("column_twice", ["impacts.csv", "line 1", "twice"],
                 csv=lambda l: [l[0].replace("vz", "vy")] + l[1:]),
    dataset_case("missing_column_z", ["impacts.csv", "line 1"],
                 csv=lambda l: [",".join(f for i, f in enumerate(r.split(",")) if i != 3)
                                for r in l]),
    dataset_case("header_only", ["impacts.csv", "samples"], csv=lambda l: l[:1]),
    dataset_case("two_rows", ["impacts.csv", "samples"], csv=lambda l: l[:3]),
    dataset_case("empty_csv", ["impacts.csv", "empty"], csv=lambda l: ""),
    dataset_case("binary_csv", ["impacts.csv", "line 2", "not a number"],
                 csv=lambda l: bytes(range(1, 256))),
    dataset_case("sidecar_format", ["rig.json", "format"],
                 sidecar=lambda s: s.update(format="vcontact.dataset/2")),
    dataset_case("sidecar_mode", ["rig.json", "mode"], sidecar=lambda s: s.update(mode="sideways")),
    dataset_case("dynamic_wrench_outputs", ["rig.json", "outputs", "position"],
                 sidecar=lambda s: s.update(mode="dynamic")),
    dataset_case("dynamic_without_mass", ["rig.json", "payload_inertia"],
                 sidecar=lambda s: s.update(mode="dynamic", outputs=["position"], noise={})),
    dataset_case("sidecar_data_missing", ["rig.json", "nowhere.csv"],
                 sidecar=lambda s: s.update(data="nowhere.csv")),
    dataset_case("sidecar_outputs_unknown", ["rig.json", "outputs"],
                 sidecar=lambda s: s.update(outputs=["fq"])),
    dataset_case("sidecar_outputs_empty", ["rig.json", "outputs"],
                 sidecar=lambda s: s.update(outputs=[])),
    dataset_case("sidecar_noise_negative", ["rig.json", "noise"],
                 sidecar=lambda s: s.update(noise={"fz": -0.03})),
    dataset_case("sidecar_noise_zero", ["rig.json", "noise"],
                 sidecar=lambda s: s.update(noise={"fz": 0})),
    dataset_case("sidecar_noise_overflow", ["rig.json", "range of a double"],
                 sidecar=lambda s: json.dumps(s).replace('"fz": 0.03', '"fz": 1e400')),
    dataset_case("sidecar_duplicate_key", ["rig.json", "mode"],
                 sidecar=lambda s: json.dumps(s).replace('"mode": "kinematic"',
                                                         '"mode": "kinematic", "mode": "x"')),
    dataset_case("sidecar_payload_halfspace", ["rig.json", "payload"],
                 sidecar=lambda s: s.update(payload={"shape": "halfspace"})),
    dataset_case("sidecar_payload_radius_negative", ["rig.json", "payload"],
                 sidecar=lambda s: s["payload"].update(radius=-0.01)),
    dataset_case("sidecar_payload_radius_tiny", ["rig.json", "payload", "1e-06"],
                 sidecar=lambda s: s["payload"].update(radius=1e-300)),
    dataset_case("sidecar_payload_radius_text", ["rig.json", "payload", "radius"],
                 sidecar=lambda s: s["payload"].update(radius="0.01")),
    dataset_case("sidecar_not_object", ["rig.json", "object"], sidecar=lambda s: "[1, 2]"),
    dataset_case("sidecar_trailing_comma", ["rig.json"],
                 sidecar=lambda s: json.dumps(s)[:-1] + ",}"),
    Case("dataset/no_such_sidecar", ["compare", "none.json", "--model", "m.json", "--out", "out"],
         ["none.json", "no such file"], outputs=["out"]),
    Case("dataset/sidecar_is_folder", ["fit", "rig.json", "--model", "m.json", "--out", "out"],
         ["rig.json", "folder"], folders=["rig.json"], outputs=["out"]),
]


def fold_case(name, extra, expect):
    """fit --fold / --merge of a kinematic record: a trajectory fit's options, refused."""
    c = dataset_case(name, expect, command="fit")
    c.args += extra
    return c


DATASET_CASES += [
    fold_case("fold_of_kinematic", ["--fold", "0"], ["--fold", "rig.json", "kinematic"]),
    fold_case("merge_of_kinematic", ["--merge", "part.json"], ["--merge", "kinematic"]),
]

MODEL_CASES = [
    model_case("kv_negative", effects(stiffness={"kv": -1.0}), ["kv"]),
    model_case("kv_nan_text", effects(stiffness={"kv": "nan"}), ["kv", "number"]),
    model_case("kv_overflow", '{"format": "vcontact.model/1", "effects": {"stiffness": '
               '{"kv": 1e400}}}', ["range of a double"]),
    model_case("mu_negative", effects(stiffness={}, coulomb={"mu": -0.2}), ["mu"]),
    model_case("unknown_effect", effects(stiffness={}, glue={}), ["glue", "unknown effect"]),
    model_case("unknown_parameter", effects(stiffness={"k": 1.0}), ["unknown parameter"]),
    model_case("parameters_not_object", effects(stiffness=[1.0]), ["stiffness"]),
    model_case("format_wrong", {"format": "vcontact.model/0", "effects": {}}, ["format"]),
    model_case("unknown_key", {"format": "vcontact.model/1", "effects": {"stiffness": {}},
                               "fit": []}, ["fit", "unknown key"]),
    model_case("fixed_unknown", {"format": "vcontact.model/1", "effects": {"stiffness": {}},
                                 "fixed": ["stiffness.k"]}, ["fixed"], command="fit"),
    model_case("fixed_not_array", {"format": "vcontact.model/1", "effects": {"stiffness": {}},
                                   "fixed": "stiffness.kv"}, ["fixed"], command="fit"),
    model_case("v_eps_negative", {"format": "vcontact.model/1", "effects": {"stiffness": {}},
                                  "settings": {"v_eps": -1}}, ["v_eps"]),
    model_case("duplicate_effect", '{"format": "vcontact.model/1", "effects": {"stiffness": {},'
               ' "stiffness": {}}}', ["stiffness"], command="diagnose"),
    model_case("not_json", "stiffness = 1", ["line 1"], command="fit"),
    model_case("empty", "", [], command="diagnose"),
    Case("dataset/synth_model_missing", ["synth", "--profile", "impacts", "--model", "none.json",
                                         "--out", "rig.json"], ["none.json", "no such file"],
         outputs=["rig.json", "rig.csv"]),
]


def synth(name, extra, expect, pending=None, profile="impacts"):
    return Case("dataset/synth_" + name,
                ["synth", "--profile", profile, "--model", "{assets}/" + TRUTH, "--out",
                 "rig.json"] + extra, expect, outputs=["rig.json", "rig.csv"], pending=pending)


SYNTH_CASES = [
    synth("samples_huge", ["--samples", "10000000000"], ["--samples"]),
    synth("samples_float", ["--samples", "1e10"], ["--samples"]),
    synth("samples_zero", ["--samples", "0"], ["--samples"]),
    synth("samples_negative", ["--samples", "-5"], ["--samples"]),
    synth("noise_negative", ["--noise-scale", "-1"], ["--noise-scale"]),
    synth("noise_nan", ["--noise-scale", "nan"], ["--noise-scale"]),
    synth("noise_huge", ["--noise-scale", "1e300"], ["--noise-scale"]),
    synth("profile_unknown", [], ["--profile"], profile="zigzag"),
    synth("seed_text", ["--seed", "abc"], ["--seed"]),
    Case("dataset/synth_out_not_json", ["synth", "--profile", "impacts", "--model",
                                        "{assets}/" + TRUTH, "--out", "rig.csv"],
         ["--out", "NAME.json"], outputs=["rig.csv"]),
    Case("dataset/synth_out_folder_missing", ["synth", "--profile", "impacts", "--model",
                                              "{assets}/" + TRUTH, "--out", "no/rig.json"],
         ["--out", "not a directory"], outputs=["no"]),
]

CASES = DATASET_CASES + MODEL_CASES + SYNTH_CASES
