"""The study file, vcontact.study/1 (docs/STUDY.md): read, checked against its base scenario,
and turned into the design (one row of parameter values per run) and the outputs per run.

Every error names the study file, the place in it (`parameters[2].uniform`) and what was
expected, before any run starts.
"""

import copy
import hashlib
import json
import math
import os
import warnings

import numpy as np

from .. import batch
from .expr import Expression, ExpressionError

FORMAT = "vcontact.study/1"
DISTRIBUTIONS = ("uniform", "normal", "lognormal")
LEVELS = ("grid", "values")
DESIGNS = ("sobol", "halton")
BUILTINS = ("completed", "stopped", "failed")  # 1 or 0 per run, for expressions
MAX_RUNS = 10_000_000
MAX_CHUNK = 100_000

BODY_FINAL = ("x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz",
              "speed", "tilt_deg")
PAIR_FIGURES = ("peak_f_n", "peak_force", "final_f_n", "contact_time", "first_contact",
                "max_patches", "impacts", "impulse", "first_impulse", "max_impulse",
                "first_restitution")
LOAD_FIGURES = ("peak_force", "final_force", "final.fx", "final.fy", "final.fz",
                "final.taux", "final.tauy", "final.tauz")
RUN_FIGURES = ("simulated_time", "steps", "rejected_steps", "contact_evaluations",
               "stop_time", "sim_wall_time")
AXES = {"x": 0, "y": 1, "z": 2}


def _standard(kind, d, xs):
    """Values as standard normal deviates of a normal (mean, std) or log-normal (median,
    sigma of the log) distribution; ±inf pass through, and x <= 0 is −inf for a log-normal."""
    if kind == "normal":
        return [(x - d["mean"]) / d["std"] for x in xs]
    return [-math.inf if x <= 0 else (math.log(x) - math.log(d["median"])) / d["sigma"]
            if math.isfinite(x) else x for x in xs]


class StudyError(ValueError):
    """A study file that cannot be run as written; the message names the file and place."""


def _canonical(value):
    return json.dumps(value, sort_keys=True, separators=(",", ":"))


def _finite(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


class Study:
    """A study file read and checked. `rows` (runs × parameters) and `names` are the design;
    `outputs` the named quantities and expressions; `identity` a digest of everything that fixes
    the results (study, base scenario text, design, chunk size), for resuming."""

    kind = "runs"

    def __init__(self, path, chunk_size=None):
        self.path = os.fspath(path)
        self.dir = os.path.dirname(os.path.abspath(self.path))
        try:
            with open(self.path, encoding="utf-8") as f:
                self.text = f.read()
        except OSError as e:
            raise StudyError(f"{self.path}: cannot read: {e.strerror}") from None
        try:
            self.doc = json.loads(self.text)
        except json.JSONDecodeError as e:
            raise StudyError(f"{self.path}: line {e.lineno}: not JSON ({e.msg})") from None
        self._read(chunk_size)

    # --- reading -------------------------------------------------------------------------

    def fail(self, where, message):
        raise StudyError(f"{self.path}: {where}: {message}")

    def _read(self, chunk_size):
        d = self.doc
        if not isinstance(d, dict):
            self.fail("top level", "expected a study object")
        allowed = {"format", "description", "scenario", "set", "parameters", "derived", "count",
                   "design", "seed", "outputs", "chunk_size"}
        for key in d:
            if key not in allowed:
                self.fail(key, f"unknown key (expected one of: {', '.join(sorted(allowed))})")
        if d.get("format") != FORMAT:
            self.fail("format", f'expected "{FORMAT}"')
        self.description = d.get("description", "")
        self._read_scenario()
        self.seed = d.get("seed", 0)
        if not isinstance(self.seed, int) or isinstance(self.seed, bool) or self.seed < 0:
            self.fail("seed", "expected an integer >= 0")
        self.design = d.get("design", "sobol")
        if self.design not in DESIGNS:
            self.fail("design", f"expected one of {', '.join(DESIGNS)}")
        self._read_parameters()
        self._read_derived()
        self._make_design()
        self._read_outputs()
        self._read_chunk_size(chunk_size)
        self.identity = hashlib.sha256("\n".join([
            _canonical(d), self.scenario_text, hashlib.sha256(self.rows.tobytes()).hexdigest(),
            str(self.chunk_size)]).encode()).hexdigest()

    def _read_scenario(self):
        if not isinstance(self.doc.get("scenario"), str):
            self.fail("scenario", "expected the base scenario's path (relative to the study file)")
        self.scenario_path = os.path.normpath(os.path.join(self.dir, self.doc["scenario"]))
        try:
            with open(self.scenario_path, encoding="utf-8") as f:
                self.scenario_text = f.read()
            self.base = json.loads(self.scenario_text)
        except OSError as e:
            self.fail("scenario", f"cannot read {self.scenario_path}: {e.strerror}")
        except json.JSONDecodeError as e:
            self.fail("scenario", f"{self.scenario_path}: line {e.lineno}: not JSON ({e.msg})")
        self.scenario_dir = os.path.dirname(self.scenario_path)
        self._read_set()
        from .. import Scenario  # the engine checks the base scenario as `simulate` would
        try:
            loaded = Scenario.load(self.scenario_path)
        except ValueError as e:
            self.fail("scenario", str(e))
        self.bodies, self.pairs = loaded.bodies, loaded.pairs
        self.loads = [l.get("name", f"load{i}") for i, l in enumerate(self.base.get("loads", []))]
        self.loads += [s.get("name", f"{s.get('a')}-{s.get('b')}")
                       for s in self.base.get("springs", [])]

    def _read_set(self):
        """"set": {path: value}: fixed changes to the base scenario for every run (a shorter
        duration, another integrator), applied before the parameters."""
        fixed = self.doc.get("set", {})
        if not isinstance(fixed, dict):
            self.fail("set", "expected an object of path: value")
        for path, value in fixed.items():
            if not (_finite(value) or isinstance(value, str)):
                self.fail(f"set.{path}", "expected a finite number or text")
            try:
                batch.set_path(self.base, path, value, raw=True)
            except ValueError as e:
                self.fail(f"set.{path}", f"{e} in {self.scenario_path}")
        if fixed:
            from .. import Scenario
            try:
                Scenario.from_json(json.dumps(self.base), self.scenario_path, self.scenario_dir)
            except ValueError as e:
                self.fail("set", str(e))

    def _paths(self, p, where):
        paths = p.get("path", [])
        paths = [paths] if isinstance(paths, str) else paths
        if not isinstance(paths, list) or not all(isinstance(s, str) for s in paths):
            self.fail(f"{where}.path", "expected a path or a list of paths")
        for k, text in enumerate(paths):
            try:
                probe = copy.deepcopy(self.base)
                batch.set_path(probe, text, 1.0)
            except ValueError as e:
                self.fail(f"{where}.path" + (f"[{k}]" if len(paths) > 1 else ""),
                          f"{e} in {self.scenario_path}")
        return paths

    def _read_parameters(self):
        params = self.doc.get("parameters")
        if not isinstance(params, list) or not params:
            self.fail("parameters", "expected a non-empty list of parameters")
        self.parameters = []
        for i, p in enumerate(params):
            where = f"parameters[{i}]"
            if not isinstance(p, dict):
                self.fail(where, "expected an object")
            name = p.get("name")
            if not isinstance(name, str) or not name.isidentifier():
                self.fail(f"{where}.name", "expected a name (letters, digits, _), for the "
                          "table's column and the expressions")
            if any(q["name"] == name for q in self.parameters) or name in BUILTINS:
                self.fail(f"{where}.name", f"'{name}' is taken")
            kinds = [k for k in DISTRIBUTIONS + LEVELS if k in p]
            if len(kinds) != 1:
                self.fail(where, "expected exactly one of " + ", ".join(DISTRIBUTIONS + LEVELS))
            for key in p:
                if key not in ("name", "path", "unit", kinds[0]):
                    self.fail(f"{where}.{key}", "unknown key (name, path, unit and one of "
                              + ", ".join(DISTRIBUTIONS + LEVELS) + ")")
            spec = {"name": name, "kind": kinds[0], "paths": self._paths(p, where),
                    "unit": p.get("unit", "")}
            spec.update(self._read_values(kinds[0], p[kinds[0]], f"{where}.{kinds[0]}"))
            self.parameters.append(spec)

    def _read_values(self, kind, v, where):
        if kind == "values":
            if not isinstance(v, list) or not v or not all(_finite(x) for x in v):
                self.fail(where, "expected a non-empty list of finite numbers")
            return {"levels": [float(x) for x in v]}
        if kind == "grid":
            keys = ("from", "to", "count")
            if not isinstance(v, dict) or set(v) != set(keys) or not all(_finite(v[k])
                                                                         for k in keys):
                self.fail(where, 'expected {"from": a, "to": b, "count": n}')
            n = v["count"]
            if not isinstance(n, int) or n < 1 or (n == 1 and v["from"] != v["to"]):
                self.fail(f"{where}.count", "expected an integer >= 2 (1 when from = to)")
            return {"levels": [float(x) for x in np.linspace(v["from"], v["to"], n)]}
        return self._read_distribution(kind, v, where)

    def _read_distribution(self, kind, v, where):
        shape = {"uniform": ("low", "high"), "normal": ("mean", "std"),
                 "lognormal": ("median", "sigma")}[kind]
        if not isinstance(v, dict) or not set(shape) <= set(v) or not set(v) <= set(shape) | {
                "low", "high"}:
            extra = ' (optionally "low", "high": truncated)' if kind != "uniform" else ""
            self.fail(where, f"expected {{{', '.join(repr(s) for s in shape)}}}{extra}")
        for k, x in v.items():
            if not _finite(x):
                self.fail(f"{where}.{k}", "expected a finite number")
        low, high = v.get("low", -math.inf), v.get("high", math.inf)
        if kind == "uniform" and not low < high:
            self.fail(where, f"low ({low}) must be below high ({high})")
        if kind == "normal" and not v["std"] > 0:
            self.fail(f"{where}.std", f"expected a standard deviation > 0, not {v['std']}")
        if kind == "lognormal":
            if not v["median"] > 0:
                self.fail(f"{where}.median", f"expected a median > 0, not {v['median']}")
            if not v["sigma"] > 0:
                self.fail(f"{where}.sigma", f"expected sigma (of the log) > 0, not {v['sigma']}")
            if "low" in v and not v["low"] > 0:
                self.fail(f"{where}.low", "a log-normal value is > 0: expected low > 0")
        if kind != "uniform" and not low < high:
            self.fail(where, f"low ({low}) must be below high ({high})")
        if kind != "uniform" and self._mass(kind, v, low, high) < 1e-12:
            self.fail(where, f"[{low}, {high}] holds no probability of the distribution")
        return {"distribution": dict(v)}

    @staticmethod
    def _mass(kind, v, low, high):
        """The probability the distribution puts in [low, high]."""
        from scipy import stats
        a, b = stats.norm.cdf(_standard(kind, v, [low, high]))
        return float(b - a)

    def _read_derived(self):
        derived = self.doc.get("derived", [])
        if not isinstance(derived, list):
            self.fail("derived", "expected a list")
        known = {p["name"] for p in self.parameters}
        self.derived = []
        for i, dv in enumerate(derived):
            where = f"derived[{i}]"
            if not isinstance(dv, dict) or set(dv) - {"path", "value"} or "value" not in dv:
                self.fail(where, 'expected {"path": ..., "value": "expression"}')
            try:
                e = Expression(dv["value"], known, f"{self.path}: {where}.value")
            except ExpressionError as err:
                raise StudyError(str(err)) from None
            self.derived.append({"paths": self._paths(dv, where), "value": e})

    # --- design --------------------------------------------------------------------------

    def _unit_sample(self, dim, n):
        from scipy.stats import qmc
        engine = (qmc.Sobol(dim, scramble=True, seed=self.seed) if self.design == "sobol"
                  else qmc.Halton(dim, scramble=True, seed=self.seed))
        with warnings.catch_warnings():  # Sobol's balance warning for n not a power of 2
            warnings.simplefilter("ignore")
            return engine.random(n)

    @staticmethod
    def _quantile(p, u):
        """The distribution's quantiles at u in (0, 1): uniform by its range; normal and
        log-normal by the inverse CDF of the standard normal on the truncated range
        [Φ(z_low), Φ(z_high)], so that a truncated distribution keeps the design's balance."""
        from scipy import stats
        d = p["distribution"]
        if p["kind"] == "uniform":
            return d["low"] + (d["high"] - d["low"]) * u
        a, b = stats.norm.cdf(_standard(p["kind"], d, [d.get("low", -math.inf),
                                                       d.get("high", math.inf)]))
        z = stats.norm.ppf(a + (b - a) * u)
        if p["kind"] == "normal":
            return d["mean"] + d["std"] * z
        return np.exp(math.log(d["median"]) + d["sigma"] * z)

    def _make_design(self):
        """Runs = count × the product of the grids' and lists' sizes: the factorial of the
        levels (the first parameter slowest), each level combination with the same `count`
        low-discrepancy points of the distributions (docs/STUDY.md, "Design")."""
        sampled = [p for p in self.parameters if p["kind"] in DISTRIBUTIONS]
        levelled = [p for p in self.parameters if p["kind"] in LEVELS]
        count = self.doc.get("count", 1 if not sampled else None)
        if not isinstance(count, int) or isinstance(count, bool) or count < 1:
            self.fail("count", "expected the number of sampled points, an integer >= 1"
                      + (" (required with distributions)" if sampled else ""))
        if not sampled and count != 1:
            self.fail("count", "the design has no distribution to sample (its runs are the "
                      "levels of the grids and lists): leave count out")
        combos = 1
        for p in levelled:
            combos *= len(p["levels"])
        self.runs = count * combos
        if self.runs > MAX_RUNS:
            self.fail("count", f"{self.runs} runs, more than the limit of {MAX_RUNS}")
        self.names = [p["name"] for p in self.parameters]
        rows = np.empty((self.runs, len(self.parameters)))
        if sampled:
            u = self._unit_sample(len(sampled), count)
            samples = np.column_stack([self._quantile(p, u[:, j]) for j, p in enumerate(sampled)])
        grid = np.array(np.meshgrid(*[p["levels"] for p in levelled], indexing="ij")).reshape(
            len(levelled), -1).T if levelled else np.zeros((1, 0))
        for j, p in enumerate(self.parameters):
            if p in sampled:
                rows[:, j] = np.tile(samples[:, sampled.index(p)], combos)
            else:
                rows[:, j] = np.repeat(grid[:, levelled.index(p)], count)
        self.rows = rows

    # --- outputs -------------------------------------------------------------------------

    def quantity_names(self):
        """Every quantity a run of the base scenario has (docs/STUDY.md, "Run quantities")."""
        names = [f"run.{f}" for f in RUN_FIGURES]
        for b in self.bodies:
            names += [f"bodies.{b}.final.{k}" for k in BODY_FINAL]
            names += [f"bodies.{b}.{m}.{a}" for m in ("min", "max") for a in AXES]
        for p in self.pairs:
            names += [f"pairs.{p}.{k}" for k in PAIR_FIGURES]
        for l in self.loads:
            names += [f"loads.{l}.{k}" for k in LOAD_FIGURES]
        return names

    def _read_outputs(self):
        outputs = self.doc.get("outputs")
        if not isinstance(outputs, list) or not outputs:
            self.fail("outputs", "expected a non-empty list of outputs")
        quantities = set(self.quantity_names())
        known = set(self.names) | set(BUILTINS)
        self.outputs, self.events = [], []
        for i, o in enumerate(outputs):
            where = f"outputs[{i}]"
            if not isinstance(o, dict):
                self.fail(where, "expected an object")
            name = o.get("name")
            if not isinstance(name, str) or not name.isidentifier() or name in known:
                self.fail(f"{where}.name", "expected a new name (letters, digits, _; not a "
                          "parameter's, another output's or " + ", ".join(BUILTINS) + ")")
            kinds = [k for k in ("quantity", "crossing", "expression") if k in o]
            if len(kinds) != 1 or set(o) - {"name", "unit", kinds[0]}:
                self.fail(where, 'expected "name", one of "quantity", "crossing", '
                          '"expression", and optionally "unit"')
            out = {"name": name, "kind": kinds[0], "unit": o.get("unit", "")}
            if kinds[0] == "quantity":
                if o["quantity"] not in quantities:
                    self.fail(f"{where}.quantity", f"no quantity '{o['quantity']}' in a run of "
                              f"{self.scenario_path}; there are: "
                              + ", ".join(sorted(quantities)))
                out["quantity"] = o["quantity"]
            elif kinds[0] == "crossing":
                out["event"] = self._read_crossing(o["crossing"], name, f"{where}.crossing")
                self.events.append(out["event"])
            else:
                try:
                    out["expression"] = Expression(o["expression"], known,
                                                   f"{self.path}: {where}.expression")
                except ExpressionError as e:
                    raise StudyError(str(e)) from None
            known.add(name)
            self.outputs.append(out)

    def _read_crossing(self, c, name, where):
        if not isinstance(c, dict) or set(c) - {"body", "coordinate", "below", "above"} or len(
                [k for k in ("below", "above") if k in c]) != 1:
            self.fail(where, '{"body": B, "coordinate": "x"|"y"|"z", "below" | "above": level}')
        if c.get("body") not in self.bodies:
            self.fail(f"{where}.body", f"no body '{c.get('body')}' (bodies: "
                      f"{', '.join(self.bodies)})")
        if c.get("coordinate") not in AXES:
            self.fail(f"{where}.coordinate", 'expected "x", "y" or "z"')
        level = c.get("below", c.get("above"))
        if not _finite(level):
            self.fail(where, "expected a finite level, m")
        return {"name": name, "body": c["body"], "axis": AXES[c["coordinate"]],
                "level": float(level), "below": "below" in c}

    def _read_chunk_size(self, chunk_size):
        given = chunk_size if chunk_size is not None else self.doc.get("chunk_size")
        if given is None:
            # ~100 chunks: enough to balance and resume, few enough that the scheduler's cost
            # per chunk (docs/STUDY.md, "Measurements") stays far below the runs'.
            given = min(1000, max(1, math.ceil(self.runs / 100)))
        if not isinstance(given, int) or isinstance(given, bool) or not 1 <= given <= MAX_CHUNK:
            self.fail("chunk_size", f"expected an integer in [1, {MAX_CHUNK}]")
        self.chunk_size = given
        self.chunks = math.ceil(self.runs / self.chunk_size)

    # --- runs ----------------------------------------------------------------------------

    def values_of(self, run):
        return dict(zip(self.names, (float(v) for v in self.rows[run])))

    def task_spec(self):
        """What a worker needs to run any chunk, as plain data (no code of the user's: the
        expressions travel as text and are checked again where they run)."""
        return {
            "identity": self.identity, "base": self.base, "scenario_path": self.scenario_path,
            "scenario_dir": self.scenario_dir, "names": self.names,
            "parameters": [{"name": p["name"], "paths": p["paths"]} for p in self.parameters],
            "derived": [{"paths": d["paths"], "value": d["value"].text} for d in self.derived],
            "outputs": [{k: (v.text if isinstance(v, Expression) else v) for k, v in o.items()}
                        for o in self.outputs],
            "events": self.events,
        }


def scenario_of(spec, values):
    """The scenario document of one run: the base with the run's parameter values set at their
    paths, then the derived values (expressions of the parameters)."""
    doc = copy.deepcopy(spec["base"])
    for p in spec["parameters"]:
        for path in p["paths"]:
            batch.set_path(doc, path, values[p["name"]])
    names = set(values)
    for d in spec["derived"]:
        v = Expression(d["value"], names, "derived")(values)
        for path in d["paths"]:
            batch.set_path(doc, path, v)
    return doc
