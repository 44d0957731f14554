#!/usr/bin/env python3
"""Turn the ContactNets cube tosses (../shared/realdata/cube-toss/raw, read by the shared
to_csv.py, which this script runs by path, never copies) into vcontact dynamic datasets.

    python3 make_datasets.py REALDATA_DIR OUT_DIR

Each toss is cut where SOURCE.md's e_q starts (3 samples before the cube's centre first falls
below h*sqrt(3), the first height at which a corner can touch) and written as OUT_DIR/toss_N.csv
(t from 0, plate frame = the record's world frame, z up, board at z = 0) with its sidecar
toss_N.json (mode dynamic, a 104.8 mm box of 0.37 kg and 0.00081 kg m^2, a half-space plate).
The velocity columns are the record's own (backward differences, median of 3), so each toss
starts from its recorded state, as in the published fits."""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

H = 0.0524  # m, the cube's half-width (SOURCE.md)
MASS, INERTIA = 0.37, 0.00081
COLUMNS = ["t", "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz"]


def convert(realdata, out_dir):
    os.makedirs(out_dir, exist_ok=True)
    with tempfile.TemporaryDirectory() as raw_csv:
        subprocess.run([sys.executable, os.path.join(realdata, "to_csv.py"), raw_csv], check=True,
                       stdout=subprocess.DEVNULL)
        names = sorted(f for f in os.listdir(raw_csv) if f.endswith(".csv"))
        for name in names:
            with open(os.path.join(raw_csv, name)) as f:
                rows = list(csv.DictReader(f))
            below = next((i for i, r in enumerate(rows) if float(r["z"]) < H * math.sqrt(3)), None)
            if below is None:
                print("skipped %s: the cube never comes near the board" % name)
                continue
            rows = rows[max(0, below - 3):]
            t0 = float(rows[0]["t"])
            stem = name[:-4]
            with open(os.path.join(out_dir, stem + ".csv"), "w") as f:
                f.write(",".join(COLUMNS) + "\n")
                for r in rows:
                    values = [float(r[c]) for c in COLUMNS]
                    values[0] -= t0
                    f.write(",".join("%.9g" % v for v in values) + "\n")
            sidecar = {
                "format": "vcontact.dataset/1", "name": stem, "data": stem + ".csv",
                "mode": "dynamic",
                "payload": {"shape": "box", "size": [2 * H, 2 * H, 2 * H]},
                "plate": {"shape": "halfspace"},
                "payload_inertia": {"mass": MASS, "inertia": [INERTIA] * 3},
                "outputs": ["position", "attitude"],
                "notes": "ContactNets cube toss %s (DAIRLab/contact-nets, BSD-3), from %s"
                         % (stem, os.path.abspath(realdata))}
            with open(os.path.join(out_dir, stem + ".json"), "w") as f:
                json.dump(sidecar, f, indent=1)
        print("wrote %d datasets to %s" % (len(names), out_dir))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    convert(sys.argv[1], sys.argv[2])
