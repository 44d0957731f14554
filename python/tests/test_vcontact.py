"""The vcontact Python package against closed forms and against the command line's files."""

import json
import math
import os
import subprocess

import numpy as np
import pytest

import vcontact

SOURCE = os.environ.get("VCONTACT_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
ASSETS = os.path.join(SOURCE, "assets")
BINARY = os.environ.get("VCONTACT_BINARY", os.path.join(SOURCE, "build", "bin", "vcontact"))

# The analytic sphere and the exact clips agree with their closed forms to 1e-9 relative
# (README, "Methods"); the tests allow that.
EXACT = 1e-9


def cap_volume(radius, h):
    return math.pi * h * h * (3 * radius - h) / 3


def test_sphere_on_halfspace_matches_the_cap_formula():
    r = vcontact.contact(vcontact.sphere(0.01), vcontact.pose((0, 0, 0.0095)),
                         vcontact.halfspace(), np.eye(4))
    assert r["in_contact"]
    assert len(r["patches"]) == 1
    agg = r["aggregate"]
    assert agg["volume"] == pytest.approx(cap_volume(0.01, 0.0005), rel=EXACT)
    assert agg["normal"] == pytest.approx([0, 0, 1], abs=EXACT)
    assert agg["depth"] == pytest.approx(0.0005, rel=EXACT)
    assert agg["area"] == pytest.approx(math.pi * (0.01**2 - 0.0095**2), rel=EXACT)
    assert agg["J_v"].shape == (3, 3) and agg["J_s"].shape == (3, 3)
    assert agg["method"] == "analytic" and agg["relative_error"] is None
    for key in ("volume", "centroid", "normal", "depth", "area", "r_gyr", "J_v", "J_s",
                "relative_error", "method", "in_contact"):
        assert key in r["patches"][0]


def test_every_pose_form_gives_the_same_contact():
    ball = vcontact.sphere(0.01)
    plate = vcontact.halfspace()
    q = (math.cos(0.2), math.sin(0.2), 0.0, 0.0)  # a turn about x: a sphere does not mind
    forms = [vcontact.pose((0, 0, 0.0095), q), ((0, 0, 0.0095), q), (0, 0, 0.0095),
             "0,0,0.0095", np.array([0, 0, 0.0095])]
    volumes = [vcontact.contact(ball, X, plate, None)["aggregate"]["volume"] for X in forms]
    assert volumes == pytest.approx([volumes[0]] * len(forms), rel=EXACT)


def test_a_pose_that_is_not_rigid_is_refused_with_the_engine_message():
    X = np.eye(4)
    X[0, 0] = 2.0
    with pytest.raises(vcontact.InputError, match="X_WA: the 4x4 array is not a rigid"):
        vcontact.contact(vcontact.sphere(0.01), X, vcontact.halfspace(), np.eye(4))


def box_arrays(a, b, c):
    v = np.array([[x, y, z] for z in (-c / 2, c / 2) for y in (-b / 2, b / 2)
                  for x in (-a / 2, a / 2)])
    f = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
                  [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]])
    return v, f


def test_a_mesh_from_arrays_clips_to_the_exact_volume_and_shares_its_storage():
    v, f = box_arrays(0.02, 0.03, 0.01)
    m = vcontact.mesh(v, f, name="brick")
    assert m.kind == "mesh"
    vertices, faces = m.arrays
    assert vertices.shape == (8, 3) and faces.shape == (12, 3)
    assert not vertices.flags.writeable
    assert vertices.base is not None  # a view of the engine's mesh, not a copy
    r = vcontact.contact(m, (0, 0, 0.004), vcontact.halfspace(), None, method="halfspace")
    assert r["aggregate"]["volume"] == pytest.approx(0.02 * 0.03 * 0.001, rel=EXACT)
    box = vcontact.contact(vcontact.box(0.02, 0.03, 0.01), (0, 0, 0.004),
                           vcontact.halfspace(), None)
    assert box["aggregate"]["volume"] == pytest.approx(r["aggregate"]["volume"], rel=EXACT)


def test_the_exact_depth_of_two_meshes_is_computed_when_asked_for():
    # A brick pressed 1 mm into a plate, both meshes: the `fast` method, whose exact depth pass
    # runs only with depth=True (docs/PYTHON.md); the depth is the slab's thickness.
    brick = vcontact.mesh(*box_arrays(0.02, 0.03, 0.01), name="brick")
    plate = vcontact.mesh(*box_arrays(0.2, 0.2, 0.05), name="plate")
    X_WA, X_WB = (0.003, -0.002, 0.004), (0.0, 0.0, -0.025)
    default = vcontact.contact(brick, X_WA, plate, X_WB)
    asked = vcontact.contact(brick, X_WA, plate, X_WB, depth=True)
    for region in [default["aggregate"]] + default["patches"]:
        assert region["method"] == "fast" and region["depth"] is None
    assert asked["aggregate"]["depth"] == pytest.approx(0.001, rel=EXACT)
    assert asked["patches"][0]["depth"] == asked["aggregate"]["depth"]
    for key in ("volume", "area", "r_gyr"):  # the same query otherwise, to the bit
        assert default["aggregate"][key] == asked["aggregate"][key]
    for key in ("centroid", "normal", "J_v", "J_s"):
        assert np.array_equal(default["aggregate"][key], asked["aggregate"][key])
    assert asked["aggregate"]["volume"] == pytest.approx(0.02 * 0.03 * 0.001, rel=EXACT)
    # a region without its depth still gives a wrench (the model does not read depth)
    model = vcontact.Model.from_dict(
        {"format": "vcontact.model/1", "effects": {"stiffness": {"kv": 4.2e12}}})
    assert model.wrench(default["aggregate"])["f_n"] == model.wrench(asked["aggregate"])["f_n"]
    # the other methods fill the depth either way
    ball = vcontact.contact(vcontact.sphere(0.01), (0, 0, 0.0095), vcontact.halfspace(), None)
    assert ball["aggregate"]["depth"] == pytest.approx(0.0005, rel=EXACT)


def test_an_open_mesh_is_refused_naming_the_defect():
    v, f = box_arrays(0.02, 0.03, 0.01)
    with pytest.raises(vcontact.InputError, match=r"brick: .*boundary edges"):
        vcontact.mesh(v, f[:-1], name="brick")
    with pytest.raises(vcontact.InputError, match="index 8 at face 0 is not a vertex"):
        vcontact.mesh(v, np.vstack([[8, 1, 2], f]), name="brick")


def test_a_mesh_file_is_scaled_into_metres():
    path = os.path.join(ASSETS, "meshes", "ball_r10mm.stl")
    metres = vcontact.load_mesh(path)
    doubled = vcontact.load_mesh(path, scale=2.0)
    size = np.ptp(metres.arrays[0], axis=0)
    assert size == pytest.approx([0.02] * 3, rel=1e-2)  # inscribed facets: slightly less
    assert np.ptp(doubled.arrays[0], axis=0) == pytest.approx(2 * size, rel=1e-12)
    with pytest.raises(vcontact.InputError, match="nothing.stl"):
        vcontact.load_mesh(os.path.join(ASSETS, "nothing.stl"))


def test_a_model_from_a_dict_gives_the_stiffness_force():
    model = vcontact.Model.from_dict(
        {"format": "vcontact.model/1", "effects": {"stiffness": {"kv": np.float64(4.2e12)}}})
    assert model.effects == ["stiffness"]
    assert model.to_dict()["effects"]["stiffness"]["kv"] == 4.2e12
    c = vcontact.contact(vcontact.sphere(0.01), (0, 0, 0.0095), vcontact.halfspace(), None)
    w = model.wrench(c["aggregate"], v_c=(0.0, 0.0, 0.0))
    # MODEL.md section 3: f_n = kv V along n.
    assert w["f_n"] == pytest.approx(4.2e12 * c["aggregate"]["volume"], rel=1e-12)
    assert w["force"] == pytest.approx([0, 0, w["f_n"]], rel=1e-12)
    assert set(w["shares"]) == {"stiffness"}
    with pytest.raises(vcontact.InputError, match="effects.stiffness"):
        vcontact.Model.from_dict({"format": "vcontact.model/1",
                                  "effects": {"stiffness": {"kv": -1}}})


def test_a_model_file_reads_as_its_dict():
    path = os.path.join(ASSETS, "datasets", "models", "drive-truth.model.json")
    model = vcontact.Model.from_file(path)
    assert model.parameters["coulomb.mu"] == 0.15
    assert vcontact.Model.from_dict(model.to_dict()).parameters == model.parameters


def test_ball_drop_runs_and_writes_what_simulate_writes(tmp_path):
    s = vcontact.Scenario.load(os.path.join(ASSETS, "scenarios", "ball_drop.json"))
    assert s.bodies == ["plate", "ball"] and s.duration == 0.3
    r = s.run(out=tmp_path)
    ball = r["bodies"]["ball"]
    n = len(ball["t"])
    assert n == 601 and ball["p"].shape == (n, 3) and ball["q"].shape == (n, 4)
    assert ball["p"][0] == pytest.approx([0, 0, 0.015])
    # It falls 5 mm onto the plate, in free fall until the first contact at sqrt(2 h / g) =
    # 31.9 ms (the output at 32 ms), and bounces, pressed in by tens of microns at most.
    pair = r["pairs"]["ball-plate"]
    first = np.flatnonzero(pair["V"] > 0)[0]
    assert pair["t"][first] == 0.032
    assert ball["p"][first - 1, 2] == pytest.approx(0.015 - 9.81 / 2 * 0.0315**2, rel=1e-6)
    assert 0.01 - 5e-5 < ball["p"][:, 2].min() < 0.01  # 21 um at the first impact
    assert pair["force"][first, 2] > 0 and pair["f_n"][first] == pytest.approx(
        pair["force"][first] @ pair["normal"][first], rel=0.25)  # friction is small at impact
    assert r["summary"]["status"] == "completed"
    csv = np.genfromtxt(tmp_path / "bodies.csv", delimiter=",", names=True, dtype=None,
                        encoding="utf-8")
    rows = csv[csv["body"] == "ball"]
    np.testing.assert_array_equal(rows["z"], ball["p"][:, 2])  # the same numbers, to the bit
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert os.path.samefile(summary["scenario"], s.path)


def test_peg_insertion_hands_over_the_drive_as_loads_csv_writes_it(tmp_path):
    s = vcontact.Scenario.load(os.path.join(ASSETS, "scenarios", "peg_insertion.json"))
    r = s.run(out=tmp_path)
    drive = r["loads"]["drive"]
    n = len(drive["t"])
    assert n == 121 and drive["force"].shape == (n, 3) and drive["torque"].shape == (n, 3)
    assert drive["p"].shape == (n, 3)
    # The drive's force is limited to 5 N (the scenario's "max_force"); at 0.12 s the target is
    # 3.5 mm below where the peg rests, so the limit holds. The limit scales the force
    # vector, so its norm is 5 N to rounding.
    assert np.linalg.norm(drive["force"][-1]) == pytest.approx(5.0, rel=1e-12)
    assert drive["force"][-1, 2] < -4.99
    csv = np.genfromtxt(tmp_path / "loads.csv", delimiter=",", names=True, dtype=None,
                        encoding="utf-8")
    rows = csv[csv["load"] == "drive"]
    np.testing.assert_array_equal(rows["t"], drive["t"])  # the same numbers, to the bit
    np.testing.assert_array_equal(rows["fz"], drive["force"][:, 2])
    np.testing.assert_array_equal(rows["tauy"], drive["torque"][:, 1])
    np.testing.assert_array_equal(rows["px"], drive["p"][:, 0])
    assert r["loads"].keys() == {"drive"}


def test_the_viewer_page_is_written_for_a_run(tmp_path):
    if not os.path.exists("/usr/share/javascript/three/three.min.js"):
        pytest.fail("libjs-three is not installed (scripts/setup.sh installs it)")
    vcontact.Scenario.load(os.path.join(ASSETS, "scenarios", "ball_drop.json")).run(out=tmp_path)
    vcontact.view(tmp_path, tmp_path / "view.html")
    page = (tmp_path / "view.html").read_text()
    assert '"name":"ball"' in page and "THREE" in page


def cli_environment():
    """The environment for the command line: this one without what CTest sets for the
    interpreter alone. A sanitizer build preloads the ASan runtime into the uninstrumented python
    (VCONTACT_INTERPRETER_ONLY names those variables, python/CMakeLists.txt); the CLI links its
    own runtime and runs with the sanitizers' defaults, leak check included."""
    env = dict(os.environ)
    for name in os.environ.get("VCONTACT_INTERPRETER_ONLY", "").split(","):
        env.pop(name, None)
    return env


def cli_json(tmp_path, command, dataset, model, name):
    out = tmp_path / command
    run = subprocess.run([BINARY, command, dataset, "--model", model, "--out", str(out)],
                         capture_output=True, text=True, env=cli_environment())
    assert run.returncode == 0, f"vcontact {command} exited {run.returncode}: {run.stderr}"
    return json.loads((out / name).read_text())


def test_compare_returns_what_compare_json_holds(tmp_path):
    dataset = os.path.join(ASSETS, "datasets", "drive.json")
    truth = os.path.join(ASSETS, "datasets", "models", "drive-truth.model.json")
    c = vcontact.compare(dataset, truth)
    # The true model of a synthetic set: residuals are its noise, chi near 1.
    assert 0.8 < c["chi"] < 1.25
    assert c == cli_json(tmp_path, "compare", dataset, truth, "compare.json")


def test_a_dataset_from_numpy_columns_compares_like_its_file():
    d = vcontact.Dataset.load(os.path.join(ASSETS, "datasets", "drive.json"))
    columns = d.columns
    assert set(("t", "x", "qw", "fx")) <= set(columns)
    again = vcontact.Dataset.from_columns(
        columns, payload={"shape": "cylinder", "radius": 0.01, "length": 0.02},
        plate={"shape": "halfspace"}, outputs=d.outputs, noise=d.noise, name="drive")
    assert again.size == d.size
    truth = os.path.join(ASSETS, "datasets", "models", "drive-truth.model.json")
    assert vcontact.compare(again, truth)["chi"] == pytest.approx(
        vcontact.compare(d, truth)["chi"], rel=1e-12)
    with pytest.raises(vcontact.InputError, match=r"dataset 'dataset': outputs: \"fq\" is not"):
        vcontact.Dataset.from_columns(columns, payload={"shape": "sphere", "radius": 0.01},
                                      plate={"shape": "halfspace"}, outputs=["fq"])


def test_fit_and_diagnose_return_what_their_files_hold(tmp_path):
    dataset = os.path.join(ASSETS, "datasets", "drive.json")
    bare = os.path.join(ASSETS, "datasets", "models", "bare.model.json")
    f = vcontact.fit(dataset, bare)
    assert f == cli_json(tmp_path, "fit", dataset, bare, "fit.json")
    assert f["model"] == json.loads((tmp_path / "fit" / "model.json").read_text())
    d = vcontact.diagnose(dataset, bare)
    d.pop("model")
    assert d == cli_json(tmp_path, "diagnose", dataset, bare, "diagnosis.json")
    assert d["verdict"] != "none"  # the bare model lacks the friction the set was made with


def test_engine_errors_are_python_exceptions_with_the_engine_message():
    with pytest.raises(vcontact.InputError, match="unknown method"):
        vcontact.contact(vcontact.sphere(0.01), None, vcontact.halfspace(), None, method="magic")
    with pytest.raises(vcontact.InputError, match="no_such.json"):
        vcontact.Scenario.load("no_such.json")
    with pytest.raises(ValueError):  # InputError is a ValueError
        vcontact.sphere(-1)


BROKEN_MODEL = {
    "format": "vcontact.model/1",
    "effects": {
        "stiffness": {},
        "broken": {"kind": "expression",
                   "parameters": {"b": {"value": 1, "unit": "N", "lower": 0, "upper": 10}},
                   "normal": "b/(V-V)"},
    },
}


def test_fit_of_a_model_predicting_inf_is_an_input_error_not_a_crash(tmp_path):
    # issue 36: an effect dividing by V - V made fit segfault (the Jacobian went unchecked)
    dataset = os.path.join(ASSETS, "datasets", "loading.json")
    model = tmp_path / "broken.model.json"
    model.write_text(json.dumps(BROKEN_MODEL))
    with pytest.raises(vcontact.InputError, match=r"effect 'broken' predicts a non-finite wrench"
                                                  r" \(f[xyz] = .*\) at sample \d+"):
        vcontact.fit(dataset, str(model))


# --- refusals of issue 36: nothing wrong, nothing lost -------------------------------------------

def test_float_face_indices_must_be_integers():
    v, f = box_arrays(0.02, 0.03, 0.01)
    assert vcontact.mesh(v, f.astype(float), name="brick").kind == "mesh"  # 1.0 is index 1
    bad = f.astype(float)
    bad[3, 1] = 2.5
    with pytest.raises(vcontact.InputError, match=r"brick: faces: index 2\.5.* at face 3 is not "
                                                  r"an integer"):
        vcontact.mesh(v, bad, name="brick")
    with pytest.raises(TypeError, match="faces: expected an array of integer vertex indices"):
        vcontact.mesh(v, f.astype(str), name="brick")


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_a_position_that_is_not_finite_is_refused_naming_the_argument(bad):
    ball, plate = vcontact.sphere(0.01), vcontact.halfspace()
    for X in [(0, 0, bad), ((0, 0, bad), (1, 0, 0, 0)), ((0, 0, 0.0095), (bad, 0, 0, 0))]:
        with pytest.raises(vcontact.InputError, match="X_WA: expected finite numbers"):
            vcontact.contact(ball, X, plate, None)


def test_a_contact_dict_with_a_nan_or_a_wrong_type_is_refused():
    model = vcontact.Model.from_dict(
        {"format": "vcontact.model/1", "effects": {"stiffness": {"kv": 4.2e12}}})
    c = vcontact.contact(vcontact.sphere(0.01), (0, 0, 0.0095), vcontact.halfspace(),
                         None)["aggregate"]
    for key in ("volume", "depth", "area", "r_gyr"):
        with pytest.raises(vcontact.InputError, match=rf"contact\['{key}'\]: expected finite"):
            model.wrench(dict(c, **{key: math.nan}))
        with pytest.raises(TypeError, match=rf"contact\['{key}'\]: expected a number, got str"):
            model.wrench(dict(c, **{key: "0.1"}))
    with pytest.raises(vcontact.InputError, match=r"contact\['centroid'\]: expected finite"):
        model.wrench(dict(c, centroid=(0, math.nan, 0)))
    with pytest.raises(TypeError, match=r"contact\['J_v'\]: expected a 3x3 array"):
        model.wrench(dict(c, J_v="identity"))
    with pytest.raises(TypeError, match=r"contact\['method'\]: expected a string"):
        model.wrench(dict(c, method=3))
    assert model.wrench(c)["f_n"] == pytest.approx(4.2e12 * c["volume"], rel=1e-12)


def test_a_repeated_json_key_is_refused_with_its_path():
    text = '{"format": "vcontact.model/1", "effects": {"stiffness": {"kv": 1e12, "kv": 2e12}}}'
    with pytest.raises(vcontact.InputError,
                       match=r"text: effects\.stiffness\.kv: the key appears twice"):
        vcontact.Model.from_json(text, "text")
    with pytest.raises(vcontact.InputError, match=r"dict: effects\.1: the key appears twice"):
        vcontact.Model.from_dict({"format": "vcontact.model/1", "effects": {1: {}, "1": {}}})


def long_scenario(tmp_path, duration, output_rate):
    with open(os.path.join(ASSETS, "scenarios", "ball_drop.json"), encoding="utf-8") as f:
        s = json.load(f)
    s.update(duration=duration, output_rate=output_rate)
    s["pairs"][0]["model"] = os.path.join(ASSETS, "scenarios", s["pairs"][0]["model"])
    path = tmp_path / "long.json"
    path.write_text(json.dumps(s), encoding="utf-8")
    return vcontact.Scenario.load(str(path))


def test_run_keeps_the_command_line_row_limit(tmp_path):
    s = long_scenario(tmp_path, 1e5, 1e3)  # 1e8 output times, two bodies
    with pytest.raises(vcontact.InputError, match="more than the limit of 50000000; lower"):
        s.run()


def test_ctrl_c_stops_a_run(tmp_path):
    import signal
    import threading
    # Uninterrupted, this run takes minutes (1e4 s in steps of at most 1 ms) and then writes
    # summary.json; a run deaf to Ctrl-C would raise KeyboardInterrupt only after that.
    s = long_scenario(tmp_path, 1e4, 0.01)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            s.run(out=tmp_path / "out")
    finally:
        timer.cancel()
    assert not (tmp_path / "out" / "summary.json").exists()
