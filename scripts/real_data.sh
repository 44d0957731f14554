#!/usr/bin/env bash
# Runs `vcontact diagnose --iterate` on the real record ../shared/realdata/mit-push-hex (a
# steel hexagonal prism pushed across plywood; see its SOURCE.md) from Coulomb + spin friction
# with kv fixed at the record's value, as issue 15 describes. The record is read in place,
# never copied; when the folder is absent (a user's clone) the script says so and exits 0.
# Not part of the README's test command.
#
#   bash scripts/real_data.sh [OUT_DIR] [VCONTACT_BINARY]
#   VCONTACT_REALDATA=/path/to/realdata bash scripts/real_data.sh
#
# OUT_DIR (default /tmp/vcontact-real-data) receives diagnosis.json, model.json,
# residuals.csv, report.html and the printed log, diagnose.txt; then the payload inertia check
# below (inertia-*.txt and folders).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
# VCONTACT_REALDATA overrides the folder (a git worktree sits deeper than the main clone).
data="${VCONTACT_REALDATA:-../shared/realdata}/mit-push-hex/hex-push.json"
out="${1:-/tmp/vcontact-real-data}"
bin="${2:-build/bin/vcontact}"
if [ ! -f "$data" ]; then
  echo "real_data.sh: $data is absent (it is not part of the repository); nothing to do"
  exit 0
fi
mkdir -p "$out"
# kv = 1e11 N/m^3 is the value the record's static sink was computed for (its notes).
cat >"$out/start.model.json" <<'MODEL'
{"format": "vcontact.model/1",
 "effects": {"stiffness": {"kv": 1e11}, "coulomb": {}, "spin": {}},
 "fixed": ["stiffness.kv"]}
MODEL
"$bin" diagnose "$data" --model "$out/start.model.json" --out "$out/diagnose" --iterate \
  | tee "$out/diagnose.txt"
echo "real_data.sh: report in $out/diagnose/report.html"

# The payload inertia rig candidate on the real record (docs/DIAGNOSIS.md). The sidecar in
# $out adds the prism's mass and inertia (SOURCE.md: 0.9827 kg, 0.001497 kg·m² about z; the x
# and y moments do not enter a planar motion) and reads the record in place:
#   as given     fx, fy, tz already hold m·a and I·α (convert.py): no inertia finding expected;
#   quasi-static the CSV's fx_qs, fy_qs, tz_qs (the same wrench without the inertial terms)
#                put in the fx, fy, tz columns of a derived CSV in $out (never in the
#                repository): the candidate should read k ≈ −1.
/usr/bin/python3 - "$data" "$out" <<'PY'
import csv, json, os, sys
data, out = os.path.abspath(sys.argv[1]), sys.argv[2]
side = json.load(open(data))
folder = os.path.dirname(data)
side["payload"]["mesh"] = os.path.join(folder, side["payload"]["mesh"])
side["payload_inertia"] = {"mass": 0.9827, "inertia": [0.0007, 0.0007, 0.001497]}
side["data"] = os.path.join(folder, side["data"])
json.dump(side, open(os.path.join(out, "inertia-as-given.json"), "w"), indent=1)
with open(side["data"]) as f:
    rows = list(csv.DictReader(f))
for r in rows:
    for c in ("fx", "fy", "tz"):
        r[c] = r[c + "_qs"]
with open(os.path.join(out, "hex-push-qs.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
    w.writeheader()
    w.writerows(rows)
side["data"] = "hex-push-qs.csv"
json.dump(side, open(os.path.join(out, "inertia-quasi-static.json"), "w"), indent=1)
PY
for v in as-given quasi-static; do
  "$bin" diagnose "$out/inertia-$v.json" --model "$out/start.model.json" --out "$out/inertia-$v"     >"$out/inertia-$v.txt"
  echo "real_data.sh: payload inertia, $v record: $(grep -m1 'verdict' "$out/inertia-$v.txt")"
  grep 'rig payload inertia' "$out/inertia-$v.txt" || echo "  (no payload inertia finding below the margin)"
done
