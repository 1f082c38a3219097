#!/usr/bin/env bash
# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
# All set-up on a Debian 12 machine: installs the Debian packages that are missing, then configures
# and builds one CMake preset (default: release). Run as root (or with sudo available).
#   scripts/setup.sh [PRESET] [EXTRA_PACKAGES...]
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
shift || true

packages=(build-essential cmake ninja-build ccache libeigen3-dev libgtest-dev nlohmann-json3-dev libcli11-dev libassimp-dev
  pkg-config libbullet-dev libosmesa6-dev libpng-dev "$@")
# the presets that build with clang: Debian 12's clang 14, its OpenMP runtime and its sanitizers' runtimes
case "$preset" in
  asan | clang | tsan) packages+=(clang libomp-dev libclang-rt-14-dev) ;;
esac
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -qq
  $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
