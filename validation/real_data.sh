#!/usr/bin/env bash
# Runs `vcontact diagnose --iterate` on the real record ../shared/realdata/mit-push-hex (a
# steel hexagonal prism pushed across plywood; see its SOURCE.md) from Coulomb + spin friction
# with kv fixed at the record's value, as issue 15 describes. The record is read in place,
# never copied; when the folder is absent (a user's clone) the script says so and exits 0.
# Not part of the README's test command.
#
#   bash validation/real_data.sh [OUT_DIR] [VCONTACT_BINARY]
#   VCONTACT_REALDATA=/path/to/realdata bash validation/real_data.sh
#
# OUT_DIR (default /tmp/vcontact-real-data) receives diagnosis.json, model.json,
# residuals.csv, report.html and the printed log, diagnose.txt.
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
