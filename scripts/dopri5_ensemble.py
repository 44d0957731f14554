#!/usr/bin/env python3
"""The discrete stepper against the spread of Dormand–Prince itself (issue 33, item 4;
docs/DISCRETE.md §5.2): a scenario run by dopri5 from its own start and from N starts whose
free bodies are moved by PERTURBATION (m, default 1 µm) in seeded random directions, and by
the discrete stepper at its defaults (or --impacts) at each --steps h:

  python3 scripts/dopri5_ensemble.py SCENARIO --out DIR [--members 6] [--perturbation 1e-6]
      [--duration S] [--output-rate HZ] [--steps 1e-3] [--impacts auto|resolve|implicit]
      [--seed 1] [--vcontact build/bin/vcontact] [--skip-reference]

Prints, per free body at the last output time, the ensemble's spread (the largest distance and
angle of a perturbed member's pose from the unperturbed run's) and each discrete run's distance
and angle from it, with "within" when both are no larger than the spread; and, for each impact
a discrete run resolved (summary.json "resolution": "resolved"), its normal impulse against the
unperturbed run's impact of the same pair nearest in start time, and that impulse's range over
the ensemble. --skip-reference reuses DIR/dopri5*/ of an earlier run.
"""
import argparse
import csv
import json
import math
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from discrete_accuracy import common_changes, run, run_discrete, variant  # noqa: E402


def last_poses(folder):
    rows = {}
    with open(os.path.join(folder, "bodies.csv"), newline="") as f:
        for row in csv.DictReader(f):
            rows[row["body"]] = {k: float(v) for k, v in row.items() if k != "body"}
    return rows


def angle(a, b):
    dot = abs(sum(a[k] * b[k] for k in ("qw", "qx", "qy", "qz")))
    na = math.sqrt(sum(a[k] ** 2 for k in ("qw", "qx", "qy", "qz")))
    nb = math.sqrt(sum(b[k] ** 2 for k in ("qw", "qx", "qy", "qz")))
    return 2.0 * math.acos(min(1.0, dot / (na * nb)))


def impacts(folder):
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)["impacts"]


def moved_start(scenario, rng, perturbation):
    """The scenario with each free body's position moved by `perturbation` in a random direction."""
    s = json.loads(json.dumps(scenario))
    for body in s["bodies"]:
        if body.get("motion", "free") != "free":
            continue
        pose = body.get("pose", [0, 0, 0, 0, 0, 0])
        values = [float(v) for v in (pose.split(",") if isinstance(pose, str) else pose)]
        values += [0.0] * (6 - len(values))
        d = [rng.gauss(0.0, 1.0) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in d))
        for i in range(3):
            values[i] += perturbation * d[i] / n
        body["pose"] = values
    return s


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scenario")
    p.add_argument("--out", required=True)
    p.add_argument("--members", type=int, default=6)
    p.add_argument("--perturbation", type=float, default=1e-6)
    p.add_argument("--duration", type=float)
    p.add_argument("--output-rate", type=float)
    p.add_argument("--steps", default="1e-3")
    p.add_argument("--impacts", choices=("auto", "resolve", "implicit"))
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--vcontact", default="build/bin/vcontact")
    p.add_argument("--skip-reference", action="store_true")
    a = p.parse_args()
    with open(a.scenario) as f:
        scenario = json.load(f)
    base = os.path.dirname(os.path.abspath(a.scenario))
    os.makedirs(a.out, exist_ok=True)
    common = common_changes(a)
    reference = dict(common, integrator="dopri5")
    rng = random.Random(a.seed)
    members = [f"dopri5_{i}" for i in range(1, a.members + 1)]
    starts = [moved_start(scenario, rng, a.perturbation) for _ in members]
    if not a.skip_reference:
        run(a.vcontact, variant(scenario, base, a.out, "dopri5", reference), a.out, "dopri5")
        for name, start in zip(members, starts):
            run(a.vcontact, variant(start, base, a.out, name, reference), a.out, name)
    discrete = run_discrete(a, scenario, base, common)

    ref = last_poses(os.path.join(a.out, "dopri5"))
    ens = [last_poses(os.path.join(a.out, m)) for m in members]
    runs = [(d, last_poses(os.path.join(a.out, d))) for d in discrete]
    free = [b for b in ref if any(ref[b][k] != 0.0 for k in ("vx", "vy", "vz", "wx", "wy", "wz"))
            or any(e[b]["x"] != ref[b]["x"] for e in ens)]
    print(f"Rest pose at t = {next(iter(ref.values()))['t']} s against {len(members)} dopri5 runs "
          f"from starts moved by {a.perturbation * 1e6:g} µm\n")
    head = "| body | ensemble spread: Δp µm, Δθ mrad |"
    rule = "|---|---|"
    for d, _ in runs:
        head += f" {d}: Δp µm, Δθ mrad |"
        rule += "---|"
    print(head + "\n" + rule)
    for b in free:
        spread_p = max(math.dist([e[b][k] for k in "xyz"], [ref[b][k] for k in "xyz"]) for e in ens)
        spread_a = max(angle(e[b], ref[b]) for e in ens)
        line = f"| {b} | {1e6 * spread_p:.3g}, {1e3 * spread_a:.3g} |"
        for _, rows in runs:
            dp = math.dist([rows[b][k] for k in "xyz"], [ref[b][k] for k in "xyz"])
            da = angle(rows[b], ref[b])
            verdict = "within" if dp <= spread_p and da <= spread_a else "outside"
            line += f" {1e6 * dp:.3g}, {1e3 * da:.3g} ({verdict}) |"
        print(line)

    ref_impacts = impacts(os.path.join(a.out, "dopri5"))
    ens_impacts = [impacts(os.path.join(a.out, m)) for m in members]

    def nearest(records, pair, start):
        same = [r for r in records if r["pair"] == pair]
        return min(same, key=lambda r: abs(r["start_s"] - start)) if same else None

    print("\nImpacts the discrete runs resolved, against the unperturbed dopri5 run's nearest of the "
          "same pair\n")
    print("| run | pair | start ms | impulse mN s | dopri5: start ms, impulse | difference | "
          "ensemble's impulses there |")
    print("|---|---|---|---|---|---|---|")
    for d in discrete:
        for r in impacts(os.path.join(a.out, d)):
            if r.get("resolution") != "resolved":
                continue
            m = nearest(ref_impacts, r["pair"], r["start_s"])
            if m is None:
                print(f"| {d} | {r['pair']} | {1e3 * r['start_s']:.2f} | "
                      f"{1e3 * r['normal_impulse_Ns']:.4g} | none | | |")
                continue
            others = [nearest(e, r["pair"], r["start_s"]) for e in ens_impacts]
            values = [1e3 * o["normal_impulse_Ns"] for o in others if o]
            rel = r["normal_impulse_Ns"] / m["normal_impulse_Ns"] - 1.0
            print(f"| {d} | {r['pair']} | {1e3 * r['start_s']:.2f} | "
                  f"{1e3 * r['normal_impulse_Ns']:.4g} | {1e3 * m['start_s']:.2f}, "
                  f"{1e3 * m['normal_impulse_Ns']:.4g} | {100 * rel:+.2f} % | "
                  f"{min(values):.4g}–{max(values):.4g} |")


if __name__ == "__main__":
    main()
