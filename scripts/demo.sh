#!/usr/bin/env bash
# Set up (scripts/setup.sh), then run the main job on a bundled example: the contact volume
# of a 10 mm steel ball, as a CAD mesh, pressed 0.5 mm into a plate, next to the exact
# sphere, so the faceting error of the mesh is in plain view.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
build="${VCONTACT_BUILD_DIR:-build}"
echo
echo "== vcontact volume assets/meshes/ball_r10mm.stl halfspace --pose-a 0,0,0.0095"
"$build/bin/vcontact" volume assets/meshes/ball_r10mm.stl halfspace --pose-a 0,0,0.0095
echo
echo "== vcontact volume sphere:0.01 halfspace --pose-a 0,0,0.0095   (the exact sphere)"
"$build/bin/vcontact" volume sphere:0.01 halfspace --pose-a 0,0,0.0095
