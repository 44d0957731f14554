#!/usr/bin/env python3
"""Impacts of a bundled scenario as a function of the discrete step, against Dormand-Prince at
tight tolerances (docs/DISCRETE.md section 5): runs `vcontact simulate` on copies of
assets/scenarios/NAME.json with "integrator", "step", "impacts" (and any overrides) changed,
and prints one row per run with the first impacts of its summary.json and its final state.

    python3 benchmarks/discrete_impacts_table.py ball_drop 2 '{"output_rate": 1000}'
    python3 benchmarks/discrete_impacts_table.py battery_box_fixture 3

Arguments: scenario name, impacts to print, JSON object of overrides; VCONTACT (environment)
names the binary (default build/bin/vcontact). Copies and outputs go to a temporary folder.
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENARIOS = os.path.join(ROOT, "assets", "scenarios")
BINARY = os.environ.get("VCONTACT", os.path.join(ROOT, "build", "bin", "vcontact"))

RUNS = [("dopri5 tight", {"integrator": "dopri5",
                          "tolerances": {"abs": 1e-11, "rel": 1e-9, "max_step": 1e-3}})]
RUNS += [(f"resolve {h * 1e3:g} ms", {"integrator": "discrete", "step": h})
         for h in (1e-3, 5e-4, 2e-4, 1e-4)]
RUNS += [(f"implicit {h * 1e3:g} ms", {"integrator": "discrete", "step": h, "impacts": "implicit"})
         for h in (1e-3, 5e-4)]


def impact_text(r):
    return (f"{r['pair']}: start {r['start_s'] * 1e3:.2f} ms, {r['duration_s'] * 1e6:.0f} us, "
            f"J {r['normal_impulse_Ns'] * 1e3:.3f} mN s, {r['approach_speed_m_s'] * 1e3:.1f} -> "
            f"{r['separation_speed_m_s'] * 1e3:.1f} mm/s, e {r['restitution']:.4f} {r['outcome']}")


def final_text(out):
    rows = list(csv.DictReader(open(os.path.join(out, "bodies.csv"))))
    last = [r for r in rows if r["t"] == rows[-1]["t"]]
    return "; ".join(f"{r['body']} vz {float(r['vz']) * 1e3:.2f} mm/s z {float(r['z']) * 1e3:.4f} mm"
                     for r in last)


def main():
    name, count = sys.argv[1], int(sys.argv[2])
    overrides = json.loads(sys.argv[3]) if len(sys.argv) > 3 else {}
    with tempfile.TemporaryDirectory() as tmp:
        for entry in os.listdir(SCENARIOS):  # the copies find their meshes and models
            os.symlink(os.path.join(SCENARIOS, entry), os.path.join(tmp, entry))
        for tag, settings in RUNS:
            scenario = json.load(open(os.path.join(SCENARIOS, name + ".json")))
            scenario.update(overrides)
            scenario.update(settings)
            path = os.path.join(tmp, "_run.json")
            json.dump(scenario, open(path, "w"))
            out = os.path.join(tmp, "out_" + tag.replace(" ", "_"))
            subprocess.run([BINARY, "simulate", "--quiet", "--out", out, path], check=True,
                           capture_output=True)
            s = json.load(open(os.path.join(out, "summary.json")))
            print(f"| {tag} | {len(s['impacts'])} impacts | {s.get('resolved_steps', 0)} / "
                  f"{s['steps']} steps resolved | {s['contact_evaluations']} queries | "
                  f"{s['wall_time_s']:.3g} s |")
            for r in s["impacts"][:count]:
                print("    " + impact_text(r))
            print("    final: " + final_text(out))


if __name__ == "__main__":
    main()
