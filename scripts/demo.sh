#!/usr/bin/env bash
# Set up (scripts/setup.sh, building only the vcontact program), then run the main job on bundled examples:
#  1. a simulation: a steel ball dropped on an aluminium plate (assets/scenarios/ball_drop.json),
#  2. the contact volume of the same ball as a CAD mesh and as the exact sphere, so that the
#     faceting error of the mesh is in plain view.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh vcontact
build="${VCONTACT_BUILD_DIR:-build}"
vcontact="$build/bin/vcontact"
echo
echo "== vcontact simulate assets/scenarios/ball_drop.json --out out/ball_drop"
"$vcontact" simulate assets/scenarios/ball_drop.json --out out/ball_drop
echo "   (body states in out/ball_drop/bodies.csv, contact quantities in out/ball_drop/pair_*.csv)"
echo
echo "== vcontact volume assets/meshes/ball_r10mm.stl halfspace --pose-a 0,0,0.0095"
"$vcontact" volume assets/meshes/ball_r10mm.stl halfspace --pose-a 0,0,0.0095
echo
echo "== vcontact volume sphere:0.01 halfspace --pose-a 0,0,0.0095   (the exact sphere)"
"$vcontact" volume sphere:0.01 halfspace --pose-a 0,0,0.0095
