#!/usr/bin/env bash
# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
# Formats the project's C++ files with clang-format (.clang-format), or with --check lists the
# files that are not formatted and fails (CI runs the check).
#   scripts/format.sh [--check]
set -euo pipefail
cd "$(dirname "$0")/.."
format="$(command -v clang-format-14 || command -v clang-format || true)"
if [ -z "$format" ]; then
  echo "format: clang-format is missing (Debian: apt-get install clang-format)" >&2
  exit 2
fi
mapfile -t files < <(git ls-files '*.h' '*.cpp')
if [ "${1:-}" = "--check" ]; then
  report="$(mktemp)"
  trap 'rm -f "$report"' EXIT
  if ! "$format" --dry-run --Werror "${files[@]}" 2> "$report"; then
    grep -o '^[^:]*:[0-9]*:[0-9]*: error' "$report" | cut -d: -f1 | sort -u | sed 's/^/not formatted: /' >&2
    echo "format: run scripts/format.sh to format them" >&2
    exit 1
  fi
  echo "format: ${#files[@]} files formatted as .clang-format says"
else
  "$format" -i "${files[@]}"
fi
