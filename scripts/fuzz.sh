#!/usr/bin/env bash
# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
# Fuzzes with libFuzzer (clang and Debian's libclang-rt-dev): load_mesh for each mesh format that
# load_mesh checks before assimp reads it, or reads in a bounded process of its own, and
# parse_scene (tests/fuzz/fuzz_scene.cpp, which also checks the message rules):
# scripts/fuzz.sh [SECONDS per target, default 240] [TARGET ...] (ply off dae gltf scene). Needs
# the release build (scripts/setup.sh release) for the libraries it does not fuzz.
# A crash, a hang (over 10 s) or a broken rule stops the run and leaves the input in build/fuzz/;
# add it as a test case once it is fixed (tests/mesh/test_load_mesh.cpp, tests/scene/). Not run by
# CI.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-240}
shift || true
targets=("${@:-ply off dae gltf scene}")
compiler=$(command -v clang++-16 || command -v clang++-14 || command -v clang++)
mkdir -p build/fuzz
release=build/release
flags=(-std=c++17 -O1 -g -fsanitize=fuzzer,address -Iinclude -I/usr/include/eigen3)
"$compiler" "${flags[@]}" -Iplugins/mesh/include tests/fuzz/fuzz_load_mesh.cpp plugins/mesh/src/*.cpp \
  "$release"/src/libcubespring.a -lassimp -fopenmp -o build/fuzz/fuzz_load_mesh
# the scene parser is compiled here, instrumented; the parts it calls come from the release build
"$compiler" "${flags[@]}" -DCUBESPRING_DATA_DIR="\"$PWD/data\"" -Iscenes/include -Iscenes/src \
  -Iplugins/bullet/include -Iplugins/render/include -Iplugins/mesh/include $(pkg-config --cflags bullet) \
  tests/fuzz/fuzz_scene.cpp scenes/src/*.cpp "$release"/plugins/bullet/libcubespring_bullet.a \
  "$release"/plugins/render/libcubespring_render.a "$release"/plugins/mesh/libcubespring_mesh.a \
  "$release"/src/libcubespring.a $(pkg-config --libs bullet) -lassimp -lOSMesa -lpng -fopenmp -o build/fuzz/fuzz_scene
for target in ${targets[@]}; do
  corpus=build/fuzz/corpus_$target
  mkdir -p "$corpus"
  cp tests/fuzz/corpus/"$target"/* "$corpus"/
  echo "fuzzing $target for $seconds s"
  if [ "$target" = scene ]; then
    # a scene file may be up to 16 MB, but the parser's work is in its structure: short inputs
    (cd build/fuzz && ./fuzz_scene "corpus_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -max_len=8192 -dict=../../tests/fuzz/scene.dict)
    continue
  fi
  # leaks inside assimp are known (tests/lsan_suppressions.txt); crashes and hangs are what count
  (cd build/fuzz && ASAN_OPTIONS=detect_leaks=0 FUZZ_EXTENSION=".$target" ./fuzz_load_mesh "corpus_$target" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096 -detect_leaks=0)
done
