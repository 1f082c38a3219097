#!/usr/bin/env bash
# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
# Fuzzes load_mesh with libFuzzer (clang and Debian's libclang-rt-dev) for each mesh format that
# load_mesh checks before assimp reads it, or reads in a bounded process of its own:
# scripts/fuzz.sh [SECONDS per format, default 240] [FORMAT ...] (ply off dae gltf). Needs the release build (scripts/setup.sh release) for the core library.
# A crash or a hang (over 10 s) stops the run and leaves the input in build/fuzz/; add it to
# tests/mesh/test_load_mesh.cpp as a case once load_mesh refuses it. Not run by CI.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-240}
shift || true
formats=("${@:-ply off dae gltf}")
compiler=$(command -v clang++-16 || command -v clang++-14 || command -v clang++)
mkdir -p build/fuzz
"$compiler" -std=c++17 -O1 -g -fsanitize=fuzzer,address -Iinclude -Iplugins/mesh/include -I/usr/include/eigen3 \
  tests/fuzz/fuzz_load_mesh.cpp plugins/mesh/src/*.cpp \
  build/release/src/libcubespring.a -lassimp -fopenmp -o build/fuzz/fuzz_load_mesh
for format in ${formats[@]}; do
  corpus=build/fuzz/corpus_$format
  mkdir -p "$corpus"
  cp tests/fuzz/corpus/"$format"/* "$corpus"/
  echo "fuzzing .$format for $seconds s"
  # leaks inside assimp are known (tests/lsan_suppressions.txt); crashes and hangs are what count
  (cd build/fuzz && ASAN_OPTIONS=detect_leaks=0 FUZZ_EXTENSION=".$format" ./fuzz_load_mesh "corpus_$format" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -max_len=4096 -detect_leaks=0)
done
