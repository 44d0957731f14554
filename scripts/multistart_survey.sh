#!/usr/bin/env bash
# How often does a single start fail where the multistart does not? (issue 15, item 1)
#
# On every bundled dataset (assets/datasets/*.json), two kinds of fit, each once from the given
# start alone (--starts 0) and once with the default multistart (16 Halton points, the three
# cheapest and the start polished):
#   complete  `fit` of the dataset's true effects (models/NAME-truth.model.json) with every
#             parameter at its library default: the user's "I know the effects, find the
#             values" fit;
#   diagnose  `diagnose` from the bare model (stiffness only): the baseline and every candidate
#             fit of the first stage (each candidate explores only the parameters it adds).
# A fit "fails" when its chi² exceeds the better of the two by more than 10: the ΔBIC margin of
# diagnose (docs/DIAGNOSIS.md), a gap that can change a verdict. The table lists every fit and
# the totals; the verdicts of the two diagnose runs are compared too.
#
#   bash scripts/multistart_survey.sh [OUT_DIR] [VCONTACT_BINARY]
#
# Takes a few minutes (2 cores). Needs Debian's python3 (/usr/bin/python3, standard library).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out="${1:-/tmp/vcontact-multistart-survey}"
bin="${2:-build/bin/vcontact}"
mkdir -p "$out"
datasets=(loading impacts friction-ramp drive dwell slide-spin rolling)
for p in "${datasets[@]}"; do
  # the truth's effects, every parameter at its default (the fixed list kept)
  /usr/bin/python3 - "assets/datasets/models/$p-truth.model.json" "$out/$p-defaults.model.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["effects"] = {k: {} for k in m["effects"]}
m.pop("fixed", None)
json.dump(m, open(sys.argv[2], "w"), indent=1)
PY
  for starts in 0 16; do
    "$bin" fit "assets/datasets/$p.json" --model "$out/$p-defaults.model.json" \
      --starts "$starts" --out "$out/$p-fit-$starts" >"$out/$p-fit-$starts.txt"
    "$bin" diagnose "assets/datasets/$p.json" --model assets/datasets/models/bare.model.json \
      --starts "$starts" --out "$out/$p-diagnose-$starts" >"$out/$p-diagnose-$starts.txt"
  done
done
/usr/bin/python3 - "$out" "${datasets[@]}" <<'PY'
import json, sys
out, names = sys.argv[1], sys.argv[2:]
MARGIN = 10.0
rows, fails = [], {"single": 0, "multi": 0}
def record(dataset, what, single, multi):
    best = min(single, multi)
    s_fail, m_fail = single > best + MARGIN, multi > best + MARGIN
    fails["single"] += s_fail
    fails["multi"] += m_fail
    rows.append((dataset, what, single, multi, "single start fails" if s_fail else
                 "multistart fails" if m_fail else ""))
verdicts = []
for p in names:
    f = [json.load(open(f"{out}/{p}-fit-{s}/fit.json")) for s in (0, 16)]
    record(p, "complete model (fit)", f[0]["comparison"]["chi2"], f[1]["comparison"]["chi2"])
    d = [json.load(open(f"{out}/{p}-diagnose-{s}/diagnosis.json")) for s in (0, 16)]
    record(p, "bare baseline", d[0]["baseline"]["chi2"], d[1]["baseline"]["chi2"])
    n = d[1]["baseline"]["chi2"] / d[1]["baseline"]["chi"] ** 2  # residual count
    chi2 = [{c["effect"]: c["chi"] ** 2 * n for c in x["ranking"] if "chi" in c} for x in d]
    for effect in sorted(chi2[1]):
        if effect in chi2[0]:
            record(p, "+ " + effect, chi2[0][effect], chi2[1][effect])
    verdicts.append((p, d[0]["verdict"], d[1]["verdict"]))
print(f"{'dataset':14} {'fit':24} {'chi2 single':>14} {'chi2 multi':>14}  outcome")
for r in rows:
    print(f"{r[0]:14} {r[1]:24} {r[2]:14.6g} {r[3]:14.6g}  {r[4]}")
print(f"\n{len(rows)} fits: the single start fails in {fails['single']}, "
      f"the multistart in {fails['multi']} (chi2 above the better by more than {MARGIN:g})")
for p, v0, v1 in verdicts:
    print(f"diagnose verdict {p:14} single start: {v0:24} multistart: {v1}")
PY
