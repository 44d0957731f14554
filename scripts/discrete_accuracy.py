#!/usr/bin/env python3
"""Runs a scenario with the Dormand–Prince integrator and with the discrete stepper at several
steps, same duration and output rate, and prints rest_pose_table.py's comparison of their last
output time (docs/DISCRETE.md §4):

  python3 scripts/discrete_accuracy.py SCENARIO --out DIR [--duration S] [--output-rate HZ]
      [--steps 1e-3,5e-4,2.5e-4] [--tolerances ABS,REL] [--vcontact build/bin/vcontact]
      [--skip-reference] [--no-sleep] [--impacts auto|resolve|implicit]

Each variant is a copy of the scenario in DIR (mesh and model paths made absolute) with
"integrator", "step", "duration", "output_rate" and, for dopri5, "tolerances" abs/rel changed;
its output goes to DIR/<variant>/ and its log (wall time, steps) to DIR/<variant>.log.
--skip-reference reuses DIR/dopri5/ from an earlier run. The discrete variants sleep as the
scenario says (on by default, docs/SLEEP.md); --no-sleep sets "sleep": false in them, for a
comparison of the awake stepper with the reference. --impacts sets "impacts" in the discrete
variants (docs/DISCRETE.md §5) and appends it to their names (discrete_1ms_implicit).
"""
import argparse
import json
import os
import subprocess
import sys

PRIMITIVES = ("sphere:", "cylinder:", "box:", "halfspace")


def absolute(path, base):
    return path if os.path.isabs(path) else os.path.normpath(os.path.join(base, path))


def variant(scenario, base, out, name, changes):
    s = json.loads(json.dumps(scenario))
    for body in s["bodies"]:
        if not body["shape"].startswith(PRIMITIVES):
            body["shape"] = absolute(body["shape"], base)
    for key, model in s.get("models", {}).items():
        if isinstance(model, str):
            s["models"][key] = absolute(model, base)
    # a pair's (or "contacts"') model is a name in "models" or a file beside the scenario
    named = s.get("models", {})
    for pair in s.get("pairs", []) + ([s["contacts"]] if "contacts" in s else []):
        model = pair.get("model")
        if isinstance(model, str) and model not in named:
            pair["model"] = absolute(model, base)
    for key, value in changes.items():
        if key == "tolerances":
            s.setdefault("tolerances", {}).update(value)
        else:
            s[key] = value
    path = os.path.join(out, f"{name}.json")
    with open(path, "w") as f:
        json.dump(s, f, indent=1)
    return path


def run(vcontact, path, out, name):
    with open(os.path.join(out, f"{name}.log"), "w") as log:
        result = subprocess.run([vcontact, "simulate", path, "--out", os.path.join(out, name),
                                 "--quiet"], stdout=log, stderr=subprocess.STDOUT)
    usage = os.times()  # CPU time of the runs so far, for the log of a long comparison
    print(f"{name}: exit {result.returncode}, CPU of the runs so far "
          f"{usage.children_user + usage.children_system:.1f} s", file=sys.stderr)
    if result.returncode != 0:
        sys.exit(f"discrete_accuracy.py: {name}: vcontact exited with {result.returncode} "
                 f"(see {out}/{name}.log)")


def common_changes(a):
    """The changes every variant gets from the command line: --duration and --output-rate."""
    common = {}
    if a.duration:
        common["duration"] = a.duration
    if a.output_rate:
        common["output_rate"] = a.output_rate
    return common


def run_discrete(a, scenario, base, common, sleep=None):
    """The discrete variants at each of --steps h (with --impacts, and "sleep" when given), run
    into a.out; their names."""
    names = []
    for h in a.steps.split(","):
        name = f"discrete_{float(h) * 1e3:g}ms" + (f"_{a.impacts}" if a.impacts else "")
        changes = dict(common, integrator="discrete", step=float(h))
        if a.impacts:
            changes["impacts"] = a.impacts
        if sleep is not None:
            changes["sleep"] = sleep
        run(a.vcontact, variant(scenario, base, a.out, name, changes), a.out, name)
        names.append(name)
    return names


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scenario")
    p.add_argument("--out", required=True)
    p.add_argument("--duration", type=float)
    p.add_argument("--output-rate", type=float)
    p.add_argument("--steps", default="1e-3,5e-4,2.5e-4")
    p.add_argument("--tolerances")
    p.add_argument("--vcontact", default="build/bin/vcontact")
    p.add_argument("--skip-reference", action="store_true")
    p.add_argument("--no-sleep", action="store_true",
                   help='the discrete variants with "sleep": false')
    p.add_argument("--impacts", choices=("auto", "resolve", "implicit"),
                   help='"impacts" of the discrete variants (default: as the scenario says)')
    a = p.parse_args()
    with open(a.scenario) as f:
        scenario = json.load(f)
    base = os.path.dirname(os.path.abspath(a.scenario))
    os.makedirs(a.out, exist_ok=True)
    common = common_changes(a)
    reference = dict(common, integrator="dopri5")
    if a.tolerances:
        abs_tol, rel_tol = (float(x) for x in a.tolerances.split(","))
        reference["tolerances"] = {"abs": abs_tol, "rel": rel_tol}
    if not a.skip_reference:
        run(a.vcontact, variant(scenario, base, a.out, "dopri5", reference), a.out, "dopri5")
    names = run_discrete(a, scenario, base, common, sleep=False if a.no_sleep else None)
    table = os.path.join(os.path.dirname(os.path.abspath(__file__)), "rest_pose_table.py")
    os.chdir(a.out)
    subprocess.run([sys.executable, table, "dopri5"] + names, check=True)


if __name__ == "__main__":
    main()
