#!/usr/bin/env bash
# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
# Set-up, then the main job. Until the surgical demo lands, the main job is the paper's cantilever:
# a 16x4x4 beam of 1 cm cells, E = 1 MPa, nu = 0.3, sagging under gravity.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh release
./build/release/apps/cubespring/cubespring measure cantilever "$@"
