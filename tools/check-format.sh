#!/usr/bin/env bash
# Fails (exit 1) when a C++ source of the tree differs from what the pinned .clang-format makes of it,
# and lists the files. Run `tools/check-format.sh --fix` to reformat them in place.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format > /dev/null || { echo "check-format: clang-format is missing (Debian package clang-format)" >&2; exit 2; }
mapfile -t files < <(find mpm analysis pipeline tests tools cmake -name '*.cpp' -o -name '*.hpp' -o -name '*.cpp.in' | sort)
if [[ "${1:-}" == "--fix" ]]; then
  clang-format -i "${files[@]}"
  exit 0
fi
bad=()
for f in "${files[@]}"; do
  clang-format --dry-run --Werror "$f" > /dev/null 2>&1 || bad+=("$f")
done
if ((${#bad[@]})); then
  printf 'not formatted by .clang-format (%d files; fix with tools/check-format.sh --fix):\n' "${#bad[@]}"
  printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "check-format: ${#files[@]} files formatted"
