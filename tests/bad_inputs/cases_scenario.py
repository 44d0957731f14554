"""Scenario files (formats/scenario_file) and the simulate command: each case changes one
thing in the bundled ball_drop scenario."""

import copy
import json

from case import Case, read_asset

MODEL = "steel_on_aluminium.model.json"


def ball_drop(assets):
    return json.loads(read_asset(assets, "scenarios/ball_drop.json"))


def scenario_case(name, change, expect, text_change=None, extra=None, pending=None):
    """change(dict) edits the scenario; text_change(str) edits its JSON text afterwards."""

    def files(assets):
        s = copy.deepcopy(ball_drop(assets))
        if change:
            change(s)
        text = json.dumps(s, indent=1)
        if text_change:
            text = text_change(text)
        out = {"scene.json": text, MODEL: read_asset(assets, "scenarios/" + MODEL)}
        out.update(extra or {})
        return out

    return Case("scenario/" + name, ["simulate", "scene.json", "--out", "out", "--quiet"],
                ["scene.json"] + expect, files=files, outputs=["out"], pending=pending)


def setter(*path_and_value):
    *path, value = path_and_value

    def change(s):
        node = s
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value

    return change


def deleter(*path):
    def change(s):
        node = s
        for key in path[:-1]:
            node = node[key]
        del node[path[-1]]

    return change


def stopping_scene(effects, **extra):
    """A steel ball 0.5 mm above a plate for 50 ms, under the model of `effects`."""
    s = {"format": "vcontact.scenario/1", "duration": 0.05, "output_rate": 1000,
         "bodies": [{"name": "plate", "shape": "halfspace", "motion": "fixed"},
                    {"name": "ball", "shape": "sphere:0.01", "density": 7900,
                     "pose": "0,0,0.0105"}],
         "pairs": [{"a": "ball", "b": "plate", "method": "analytic",
                    "model": {"format": "vcontact.model/1", "effects": effects}}]}
    s.update(extra)
    return s


BALL = ("bodies", 1)
PAIR = ("pairs", 0)

CASES = [
    scenario_case("duration_negative", setter("duration", -1), ["duration"]),
    scenario_case("duration_zero", setter("duration", 0), ["duration"]),
    scenario_case("duration_huge", setter("duration", 1e12), ["duration"]),
    scenario_case("duration_string", setter("duration", "0.3"), ["duration"]),
    scenario_case("duration_overflow", None, ["duration", "range of a double"],
                  text_change=lambda t: t.replace('"duration": 0.3', '"duration": 1e400')),
    scenario_case("duration_twice", None, ["duration"],
                  text_change=lambda t: t.replace('"duration": 0.3',
                                                  '"duration": 0.3, "duration": 100')),
    scenario_case("output_rate_zero", setter("output_rate", 0), ["output_rate"]),
    scenario_case("output_rate_absurd", setter("output_rate", 1e9), ["output_rate", "1e+06"]),
    scenario_case("gravity_two", setter("gravity", [0, -9.81]), ["gravity", "3 numbers"]),
    scenario_case("gravity_string", setter("gravity", "down"), ["gravity"]),
    scenario_case("gravity_huge", setter("gravity", [0, 0, -1e9]), ["gravity", "1000"]),
    scenario_case("tolerance_negative", setter("tolerances", "abs", -1e-9), ["tolerances.abs"]),
    scenario_case("tolerance_unknown_key", setter("tolerances", "absolute", 1e-9),
                  ["tolerances", "absolute"]),
    scenario_case("max_step_zero", setter("tolerances", "max_step", 0), ["tolerances.max_step"]),
    scenario_case("description_object", setter("description", {"a": 1}), ["description"]),
    scenario_case("format_wrong", setter("format", "vcontact.scenario/9"), ["format"]),
    scenario_case("format_missing", deleter("format"), ["format"]),
    scenario_case("unknown_top_key", setter("durations", 1), ["durations"]),
    scenario_case("bodies_empty", setter("bodies", []), ["bodies"]),
    scenario_case("bodies_object", setter("bodies", {}), ["bodies"]),
    scenario_case("body_density_negative", setter(*BALL, "density", -7900),
                  ["bodies[1].density"]),
    scenario_case("body_density_zero", setter(*BALL, "density", 0), ["bodies[1].density"]),
    scenario_case("body_density_absurd", setter(*BALL, "density", 1e9),
                  ["bodies[1].density", "100000"]),
    scenario_case("body_density_tiny", setter(*BALL, "density", 1e-3),
                  ["bodies[1].density", "0.1"]),
    scenario_case("body_density_null", setter(*BALL, "density", None), ["bodies[1].density"]),
    scenario_case("body_mass_without_inertia",
                  lambda s: (s["bodies"][1].pop("density"), s["bodies"][1].update(mass=1.0)),
                  ["bodies[1].inertia"]),
    scenario_case("body_inertia_triangle",
                  lambda s: (s["bodies"][1].pop("density"),
                             s["bodies"][1].update(mass=1.0, inertia=[1.0, 1.0, 5.0])),
                  ["bodies[1].inertia", "triangle"]),
    scenario_case("body_inertia_not_definite",
                  lambda s: (s["bodies"][1].pop("density"),
                             s["bodies"][1].update(mass=1.0, inertia=[1, 0, 0, 0, 1, 2, 0, 2, 1])),
                  ["bodies[1].inertia", "positive definite"]),
    scenario_case("body_inertia_negative",
                  lambda s: (s["bodies"][1].pop("density"),
                             s["bodies"][1].update(mass=1.0, inertia=[-1.0, 1.0, 1.0])),
                  ["bodies[1].inertia"]),
    scenario_case("body_inertia_eight", lambda s: (s["bodies"][1].pop("density"),
                                                   s["bodies"][1].update(mass=1.0,
                                                                         inertia=[1] * 8)),
                  ["bodies[1].inertia", "9 numbers"]),
    scenario_case("body_mass_huge",
                  lambda s: (s["bodies"][1].pop("density"),
                             s["bodies"][1].update(mass=1e30, inertia=[1.0, 1.0, 1.0])),
                  ["bodies[1].mass"]),
    scenario_case("body_pose_trailing_comma", setter(*BALL, "pose", "0,0,0.015,"),
                  ["bodies[1].pose", "not a number"]),
    scenario_case("body_pose_hex", setter(*BALL, "pose", "0,0,0x1"),
                  ["bodies[1].pose", "not a number"]),
    scenario_case("body_pose_far", setter(*BALL, "pose", "0,0,1e7"), ["bodies[1].pose", "1000"]),
    scenario_case("body_pose_angle", setter(*BALL, "pose", "0,0,0.015,0,0,1000"),
                  ["bodies[1].pose", "360"]),
    scenario_case("body_shape_nan", setter(*BALL, "shape", "sphere:nan"),
                  ["bodies[1].shape", "not a number"]),
    scenario_case("body_shape_tiny", setter(*BALL, "shape", "sphere:1e-300"),
                  ["bodies[1].shape", "1e-06"]),
    scenario_case("body_shape_number", setter(*BALL, "shape", 0.01), ["bodies[1].shape"]),
    scenario_case("body_missing_mesh", setter(*BALL, "shape", "meshes/nowhere.stl"),
                  ["bodies[1].shape", "nowhere.stl", "no such file"]),
    scenario_case("body_velocity_nan_text", setter(*BALL, "velocity", [0, 0, "nan"]),
                  ["bodies[1].velocity"]),
    scenario_case("body_velocity_absurd", setter(*BALL, "velocity", [0, 0, 1e12]),
                  ["bodies[1].velocity"]),
    scenario_case("body_angular_velocity_absurd", setter(*BALL, "angular_velocity", [1e12, 0, 0]),
                  ["bodies[1].angular_velocity"]),
    scenario_case("body_motion_unknown", setter(*BALL, "motion", "flying"), ["bodies[1].motion"]),
    scenario_case("body_name_twice", setter(*BALL, "name", "plate"), ["plate"]),
    scenario_case("body_unknown_key", setter(*BALL, "colour", "red"), ["bodies[1]", "colour"]),
    scenario_case("pair_unknown_body", setter(*PAIR, "a", "cube"), ["pairs[0]", "cube"]),
    scenario_case("pair_model_missing_file", setter(*PAIR, "model", "nowhere.model.json"),
                  ["pairs[0].model", "nowhere.model.json"]),
    scenario_case("pair_method_unknown", setter(*PAIR, "method", "magic"),
                  ["pairs[0].method"]),
    scenario_case("pair_model_negative_kv", setter(*PAIR, "model",
                                                   {"format": "vcontact.model/1",
                                                    "effects": {"stiffness": {"kv": -1}}}),
                  ["pairs[0].model", "kv"]),
    scenario_case("trailing_comma", None, ["line"],
                  text_change=lambda t: t.rstrip().rstrip("}") + ",}"),
    scenario_case("not_json", None, ["line 1"], text_change=lambda t: "duration = 0.3\n"),
    scenario_case("empty_file", None, [], text_change=lambda t: ""),
    scenario_case("top_level_array", None, ["object"], text_change=lambda t: "[" + t + "]"),
    scenario_case("prescribed_frequency_absurd",
                  lambda s: s["bodies"][1].update(motion="prescribed", prescribed={
                      "velocity": [0, 0, -0.01], "amplitude": [0, 0, 0.001], "frequency": 1e8}),
                  ["bodies[1].prescribed.frequency"]),
    # Prescribed motion from a table, loads and springs (docs/SCENARIO.md).
    scenario_case("motion_csv_missing",
                  lambda s: (s["bodies"][1].pop("pose"),
                             s["bodies"][1].update(motion={"csv": "nowhere.csv"})),
                  ["bodies[1].motion.csv", "nowhere.csv", "cannot be read"]),
    scenario_case("motion_csv_time_not_increasing",
                  lambda s: (s["bodies"][1].pop("pose"),
                             s["bodies"][1].update(motion={"csv": "path.csv"})),
                  ["bodies[1].motion.csv", "path.csv", "line 3, column t",
                   "strictly increasing"],
                  extra={"path.csv": "t,x,y,z,qw,qx,qy,qz\n0,0,0,0.02,1,0,0,0\n"
                                     "0,0,0,0.01,1,0,0,0\n"}),
    scenario_case("motion_csv_not_a_number",
                  lambda s: (s["bodies"][1].pop("pose"),
                             s["bodies"][1].update(motion={"csv": "path.csv"})),
                  ["bodies[1].motion.csv", "path.csv", "line 2", "not a number"],
                  extra={"path.csv": "t,x,y,z,qw,qx,qy,qz\n0,0,0,0.02x,1,0,0,0\n"}),
    scenario_case("motion_csv_unknown_column",
                  lambda s: (s["bodies"][1].pop("pose"),
                             s["bodies"][1].update(motion={"csv": "path.csv"})),
                  ["bodies[1].motion.csv", "unknown column 'roll'"],
                  extra={"path.csv": "t,x,y,z,qw,qx,qy,qz,roll\n0,0,0,0.02,1,0,0,0,0\n"}),
    scenario_case("load_negative_stiffness",
                  setter("loads", [{"body": "ball", "target": {"pose": "0,0,0.01"},
                                    "stiffness": -100}]),
                  ["loads[0].stiffness", "[0, 1e+12] N/m", "-100"]),
    scenario_case("load_unknown_key",
                  setter("loads", [{"body": "ball", "force": [0, 0, 1], "colour": "red"}]),
                  ["loads[0].colour", "unknown key"]),
    scenario_case("load_csv_missing",
                  setter("loads", [{"body": "ball", "csv": "forces.csv"}]),
                  ["loads[0].csv", "forces.csv", "cannot be read"]),
    scenario_case("spring_negative_damping",
                  setter("springs", [{"a": "ball", "b": "plate", "stiffness": 10,
                                      "damping": -1}]),
                  ["springs[0].damping", "N s/m"]),
    scenario_case("spring_unknown_body",
                  setter("springs", [{"a": "ball", "b": "anvil", "stiffness": 10}]),
                  ["springs[0].b", "no body named 'anvil'"]),
    Case("scenario/no_such_file", ["simulate", "missing.json", "--out", "out", "--quiet"],
         ["missing.json", "no such file"], outputs=["out"]),
    Case("scenario/folder_given", ["simulate", "scenes", "--out", "out", "--quiet"],
         ["scenes", "folder"], folders=["scenes"], outputs=["out"]),
] + [
    # Runs that stop (exit 3) keep their output; the message names the time and the body.
    Case("scenario/stops_on_nan_from_an_expression",
         ["simulate", "scene.json", "--out", "out", "--quiet"],
         ["simulation stopped: t = ", "'ball'", "not finite"], code=3,
         files=lambda assets: {"scene.json": json.dumps(stopping_scene({
             "stiffness": {"kv": 5.17e12},
             "root_damping": {"kind": "expression", "normal": "c*sqrt(ddot)", "parameters": {
                 "c": {"value": 1, "unit": "N s^0.5/m^0.5", "lower": 0, "upper": 1000}}}}))}),
    Case("scenario/stops_on_blow_up",
         ["simulate", "scene.json", "--out", "out", "--quiet"],
         ["simulation stopped: t = ", "body 'ball'", "kinetic energy"], code=3,
         files=lambda assets: {"scene.json": json.dumps(stopping_scene(
             {"stiffness": {"kv": 1e18}}, integrator="bdf",
             tolerances={"abs": 1e-2, "rel": 1e-2}))}),
]
