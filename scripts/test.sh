#!/usr/bin/env bash
# Set up (scripts/setup.sh), then run the whole test suite through CTest.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
build="${VCONTACT_BUILD_DIR:-build}"
ctest --test-dir "$build" --output-on-failure -j"${VCONTACT_JOBS:-$(nproc)}"
