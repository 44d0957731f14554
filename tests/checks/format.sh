#!/usr/bin/env bash
# Fails when a tracked .cpp/.hpp differs from what clang-format makes of it (the repository's
# .clang-format). Exits 77 (CTest: skipped) when clang-format or git is not installed.
#
#   bash tests/checks/format.sh SOURCE_DIR
set -euo pipefail
src="${1:?usage: format.sh SOURCE_DIR}"
clang_format="${CLANG_FORMAT:-clang-format}"
for tool in "$clang_format" git; do
  if ! command -v "$tool" >/dev/null; then
    echo "format: skipped, $tool is not installed (scripts/setup.sh installs it)"
    exit 77
  fi
done
cd "$src"
mapfile -t files < <(git ls-files '*.cpp' '*.hpp')
if ! "$clang_format" --dry-run --Werror "${files[@]}"; then
  echo "format: run clang-format -i on the files above" >&2
  exit 1
fi
echo "format: ${#files[@]} files match .clang-format ($("$clang_format" --version))"
