#!/usr/bin/env bash
# The cube-toss worked example (README.md here): the 456 shared ContactNets tosses as dynamic
# datasets, one model fitted to all of them with 5-fold cross-validation by toss, and the
# reports.
#
#   bash examples/cube_toss/run.sh [OUT]       (from the repository root; OUT default out/cube_toss)
#
# Needs ../shared/realdata/cube-toss (relative to the repository root) and build/bin/vcontact.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
realdata=${VCONTACT_REALDATA:-$root/../shared/realdata}/cube-toss
vcontact=${VCONTACT:-$root/build/bin/vcontact}
out=${1:-out/cube_toss}
if [ ! -d "$realdata/raw" ]; then
  echo "cube_toss: $realdata/raw is not here; this example reads the shared tosses" >&2
  exit 1
fi
python3 "$here/make_datasets.py" "$realdata" "$out/datasets"
"$vcontact" fit "$out/datasets" --model "$here/start.model.json" --out "$out/fit" \
  --folds "${FOLDS:-5}" ${FIT_OPTIONS:-}
# one toss replayed by the fitted model, with the fitted plate offset
offset=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['plate_offset_m'])" "$out/fit/fit.json")
"$vcontact" compare "$out/datasets/toss_0.json" --model "$out/fit/model.json" \
  --plate-offset "$offset" --out "$out/toss_0"
echo "reports: $out/fit/report.html (all tosses), $out/toss_0/report.html (toss 0)"
