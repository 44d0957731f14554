#!/usr/bin/env python3
"""Compares the last output time of `vcontact simulate` runs with a reference run of the same
scenario (docs/DISCRETE.md §4): per free body, the distance between the body-frame origins
(µm; in brackets its vertical part, the run's z minus the reference's), the angle between the attitudes (mrad, the rotation taking one to the other), and the
speed |v| and angular speed |w| of each run at that time.

  python3 scripts/rest_pose_table.py REFERENCE_DIR RUN_DIR [RUN_DIR ...]

Each folder holds a bodies.csv; the runs must end at the same time. Prints a Markdown table:
one row per body, one group of columns per run. Bodies that never move (fixed) are left out.
"""
import csv
import math
import sys


def last_rows(folder):
    """{body: last row} of folder/bodies.csv and the time of that row."""
    rows = {}
    with open(f"{folder}/bodies.csv", newline="") as f:
        for row in csv.DictReader(f):
            rows[row["body"]] = {k: float(v) for k, v in row.items() if k != "body"}
    times = {r["t"] for r in rows.values()}
    if len(times) != 1:
        sys.exit(f"rest_pose_table.py: {folder}/bodies.csv: the bodies end at different times")
    return rows, times.pop()


def norm(r, keys):
    return math.sqrt(sum(r[k] ** 2 for k in keys))


def angle(a, b):
    dot = abs(sum(a[k] * b[k] for k in ("qw", "qx", "qy", "qz")))
    dot /= norm(a, ("qw", "qx", "qy", "qz")) * norm(b, ("qw", "qx", "qy", "qz"))
    return 2.0 * math.acos(min(1.0, dot))


def moved(rows_by_time, body):
    return any(abs(r[body][k]) > 0 for r in rows_by_time for k in ("vx", "vy", "vz", "wx", "wy", "wz"))


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    ref, t_ref = last_rows(sys.argv[1])
    runs = []
    for folder in sys.argv[2:]:
        rows, t = last_rows(folder)
        if abs(t - t_ref) > 1e-12 or set(rows) != set(ref):
            sys.exit(f"rest_pose_table.py: {folder}: ends at t = {t} with bodies {sorted(rows)}, "
                     f"the reference at t = {t_ref} with {sorted(ref)}")
        runs.append((folder, rows))
    head = "| body | reference: v mm/s, w rad/s |"
    rule = "|---|---|"
    for folder, _ in runs:
        head += f" {folder}: Δp µm (Δz), Δθ mrad, v mm/s, w rad/s |"
        rule += "---|"
    print(f"t = {t_ref} s\n\n{head}\n{rule}")
    for body, r in ref.items():
        if not moved([ref] + [rows for _, rows in runs], body):
            continue
        line = f"| {body} | {1e3 * norm(r, ('vx', 'vy', 'vz')):.3g}, {norm(r, ('wx', 'wy', 'wz')):.3g} |"
        for _, rows in runs:
            q = rows[body]
            dp = math.dist([r[k] for k in "xyz"], [q[k] for k in "xyz"])
            dz = q["z"] - r["z"]
            line += (f" {1e6 * dp:.3g} ({1e6 * dz:+.2g}), {1e3 * angle(r, q):.3g}, "
                     f"{1e3 * norm(q, ('vx', 'vy', 'vz')):.3g}, {norm(q, ('wx', 'wy', 'wz')):.3g} |")
        print(line)


if __name__ == "__main__":
    main()
