#!/usr/bin/env bash
# Checks that every C++ file of dem/, coupling/ and tests/ is formatted as .clang-format says (clang-format 14,
# Debian's; scripts/setup.sh installs it). Exit 1 naming each file that is not, with the command that formats it.
#
#   bash tests/docs/check_format.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
if ! command -v clang-format >/dev/null; then
  echo "check_format: clang-format is not installed (bash scripts/setup.sh installs it)" >&2
  exit 1
fi
mapfile -t files < <(git ls-files 'dem/*.cpp' 'dem/*.h' 'coupling/*.cpp' 'coupling/*.h' 'tests/*.cpp' 'tests/*.h')
# One clang-format for all (a process per file takes 20 s): its warnings name each file and line.
if ! out=$(clang-format --dry-run -Werror --style=file "${files[@]}" 2>&1); then
  mapfile -t bad < <(grep -oE '^[^:]+\.(cpp|h):[0-9]+:[0-9]+: error' <<<"$out" | cut -d: -f1 | sort -u)
  printf 'check_format: not formatted: %s\n' "${bad[@]}" >&2
  echo "check_format: format them with: clang-format -i --style=file ${bad[*]}" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files formatted as .clang-format says"
