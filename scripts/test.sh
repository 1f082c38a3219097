#!/usr/bin/env bash
# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
# Set-up, then the whole test suite: every label, the CalculiX validation included.
#   scripts/test.sh [PRESET]   (default dev; the asan preset skips the slow validation labels)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-dev}"
scripts/setup.sh "$preset" calculix-ccx
ctest --preset "$preset" -j 2
