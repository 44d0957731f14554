"""One chunk of a study's runs, on whichever process runs it (a Dask worker or the client).

run_chunk is pure: the same arguments give the same rows, to the bit, wherever and however often
it runs (only the wall times differ), so a chunk lost with its worker is simply run again and a
finished chunk never needs to be. The rows carry everything the table needs, so the client only
writes them.
"""

import json
import math

import numpy as np

from .. import _vcontact
from .expr import Expression
from .spec import BUILTINS, scenario_of


def _tilt_deg(q):
    """Angle between the body's z axis and the world's, degrees: R_zz = 1 − 2 (qx² + qy²)."""
    w, x, y, z = q
    return math.degrees(math.acos(max(-1.0, min(1.0, 1.0 - 2.0 * (x * x + y * y)))))


def quantity(result, name):
    """The value of a run quantity (docs/STUDY.md, "Run quantities") in a run_batch result; nan
    where the run has none (an error before the run, no impact)."""
    part, _, rest = name.partition(".")
    if part == "run":
        if rest == "stop_time":
            return float(result["stop_time"])
        if rest == "sim_wall_time":
            return float(result["sim"]["wall_time"]) if result["sim"] else math.nan
        return float(result["sim"][rest]) if result["sim"] else math.nan
    table = result[part]
    owner = next((k for k in table if rest.startswith(k + ".")), None)
    if owner is None:
        return math.nan  # a run that failed before its scenario was read has no bodies
    figure = rest[len(owner) + 1:]
    f = table[owner]
    if part == "bodies":
        return _body(f, figure)
    if part == "pairs":
        return _pair(f, figure)
    return _load(f, figure)


def _body(f, figure):
    kind, _, axis = figure.partition(".")
    if kind in ("min", "max"):
        return float(f[kind + "_p"]["xyz".index(axis)])
    finals = {"x": f["final_p"][0], "y": f["final_p"][1], "z": f["final_p"][2],
              "qw": f["final_q"][0], "qx": f["final_q"][1], "qy": f["final_q"][2],
              "qz": f["final_q"][3], "vx": f["final_v"][0], "vy": f["final_v"][1],
              "vz": f["final_v"][2], "wx": f["final_w"][0], "wy": f["final_w"][1],
              "wz": f["final_w"][2]}
    if axis == "speed":
        return float(np.linalg.norm(f["final_v"]))
    if axis == "tilt_deg":
        return _tilt_deg(f["final_q"]) if not np.isnan(f["final_q"][0]) else math.nan
    return float(finals[axis])


def _pair(f, figure):
    impulses = f["impacts"]["normal_impulse_Ns"]
    derived = {
        "impacts": lambda: float(len(impulses)),
        "impulse": lambda: float(np.sum(impulses)),
        "first_impulse": lambda: float(impulses[0]) if len(impulses) else math.nan,
        "max_impulse": lambda: float(np.max(impulses)) if len(impulses) else math.nan,
        "first_restitution": lambda: (float(f["impacts"]["restitution"][0]) if len(impulses)
                                      else math.nan),
    }
    return derived[figure]() if figure in derived else float(f[figure])


def _load(f, figure):
    if figure == "final_force":
        return float(np.linalg.norm(f["final_force"]))
    if figure.startswith("final."):
        c = figure[len("final."):]
        vec = f["final_force"] if c.startswith("f") else f["final_torque"]
        return float(vec["xyz".index(c[-1])])
    return float(f[figure])


def outputs_of(spec, values, result, compiled):
    """The run's outputs in the study's order: quantities, crossing times, then expressions over
    the parameters, the outputs before them and completed/stopped/failed."""
    env = dict(values)
    env.update({"completed": float(result["status"] == "completed"),
                "stopped": float(result["status"] == "stopped"),
                "failed": float(result["status"] == "error")})
    row = []
    for o in spec["outputs"]:
        if o["kind"] == "quantity":
            v = quantity(result, o["quantity"])
        elif o["kind"] == "crossing":
            v = float(result["events"].get(o["name"], math.nan))
        else:
            v = compiled[o["name"]](env)
        env[o["name"]] = v
        row.append(v)
    return row


def compile_outputs(spec):
    known = set(spec["names"]) | set(BUILTINS)
    compiled = {}
    for o in spec["outputs"]:
        if o["kind"] == "expression":
            compiled[o["name"]] = Expression(o["expression"], known, o["name"])
        known.add(o["name"])
    return compiled


def run_chunk(spec, chunk, first, rows, threads=1):
    """Runs rows (parameter values, one row per run, runs first, first + 1, ...) and returns
    {"identity", "chunk", "rows": [{run, status, message, wall_time, outputs}]}."""
    names = spec["names"]
    items, errors = [], {}
    for k, row in enumerate(rows):
        values = dict(zip(names, map(float, row)))
        source = f"{spec['scenario_path']} (run {first + k})"
        try:
            items.append((json.dumps(scenario_of(spec, values)), source, spec["scenario_dir"]))
        except ValueError as e:  # a derived value the path cannot take
            errors[k] = str(e)
            items.append(("{}", source, spec["scenario_dir"]))
    results = _vcontact.run_batch(items, spec["events"], threads)
    compiled = compile_outputs(spec)
    out = []
    for k, (row, result) in enumerate(zip(rows, results)):
        if k in errors:
            result["message"] = errors[k]
        values = dict(zip(names, map(float, row)))
        out.append({"run": first + k, "status": result["status"], "message": result["message"],
                    "wall_time": result["wall_time"], "cpu_time": result["cpu_time"],
                    "outputs": outputs_of(spec, values, result, compiled)})
    return {"identity": spec["identity"], "chunk": chunk, "rows": out}
