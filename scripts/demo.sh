#!/usr/bin/env bash
# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
# Set-up, then the main job: the headless surgical demo. With no argument, cubespring plays the
# default scene (data/scenes/liver_probe.json: a probe presses into a liver with a tumour, drags
# across it and lets go) and writes PNG frames, tool_forces.csv and tool_force.png to
# ./cubespring-demo-output; arguments go to cubespring (e.g. `run SCENE.json --frames 12`).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh release
./build/release/apps/cubespring/cubespring "$@"
