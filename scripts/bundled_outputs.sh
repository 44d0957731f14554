#!/usr/bin/env bash
# Runs every bundled example through the engine and writes what it produced under OUT_DIR, so
# that two builds can be compared file by file (a refactoring must leave them byte-identical):
#
#   bash scripts/bundled_outputs.sh OUT_DIR [VCONTACT_BINARY]
#   diff -rq OUT_A OUT_B        # or: cmp each file
#
# - every scenario of assets/scenarios/ (simulate: bodies.csv, pair_*.csv);
# - every dataset of assets/datasets/: compare with its true model, fit and diagnose --iterate
#   from the bare model (the JSON files and residuals.csv);
# - synth of every profile with its true model and the bundled seed;
# - volume of the demo's ball as a mesh and as a sphere (--json), and friction-map.
# Files that carry wall-clock times (summary.json, report.html, the printed logs) are left in
# OUT_DIR/logs and are not meant to compare equal.
#
# Every run is pinned to one CPU (taskset, where installed). Builds before 7977cbf summed the
# columns grid in a TBB reduction whose order followed the thread scheduling, so their
# friction_map.csv and distributed-friction runs changed in the last digits from run to run on
# several threads; pinned, they compare with builds since, whose reduction is deterministic.
#
# Environment: VCONTACT_SKIP_SLOW=1 leaves out punch_lumped_vs_distributed (about 12 s alone).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out="${1:?usage: bundled_outputs.sh OUT_DIR [VCONTACT_BINARY]}"
bin="${2:-build/bin/vcontact}"
mkdir -p "$out/logs" "$out/synth"
log() { echo "bundled_outputs: $*" >&2; }
pin=()
if command -v taskset >/dev/null; then  # the first CPU this shell may run on
  pin=(taskset -c "$(taskset -pc $$ | sed 's/.*: //; s/[,-].*//')")
fi
run() { "${pin[@]}" "$bin" "$@"; }

for s in assets/scenarios/*.json; do
  name=$(basename "$s" .json)
  case "$name" in *.model) continue ;; esac
  if [ "${VCONTACT_SKIP_SLOW:-0}" = 1 ] && [ "$name" = punch_lumped_vs_distributed ]; then
    continue
  fi
  log "simulate $name"
  run simulate "$s" --out "$out/simulate/$name" --quiet >"$out/logs/simulate_$name.txt"
  mv "$out/simulate/$name/summary.json" "$out/logs/summary_$name.json"
done

bare=assets/datasets/models/bare.model.json
for d in assets/datasets/*.json; do
  name=$(basename "$d" .json)
  truth=assets/datasets/models/$name-truth.model.json
  log "compare/fit/diagnose $name"
  run compare "$d" --model "$truth" --out "$out/compare/$name" >"$out/logs/compare_$name.txt"
  run fit "$d" --model "$bare" --out "$out/fit/$name" >"$out/logs/fit_$name.txt"
  run diagnose "$d" --model "$bare" --out "$out/diagnose/$name" --iterate \
    >"$out/logs/diagnose_$name.txt"
  for dir in compare fit diagnose; do
    mv "$out/$dir/$name/report.html" "$out/logs/report_${dir}_$name.html"
  done
  log "synth $name"
  run synth --profile "$name" --model "$truth" --samples 1200 --seed 2026 \
    --out "$out/synth/$name.json" >"$out/logs/synth_$name.txt"
done

log "volume"
mkdir -p "$out/volume"
run volume assets/meshes/ball_r10mm.stl halfspace --pose-a 0,0,0.0095 --json \
  >"$out/volume/ball_mesh.json"
run volume sphere:0.01 halfspace --pose-a 0,0,0.0095 --json >"$out/volume/ball_sphere.json"
log "friction-map"
run friction-map --out "$out/friction_map.csv" >"$out/logs/friction_map.txt"
log "done: $out"
