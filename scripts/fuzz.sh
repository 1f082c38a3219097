#!/usr/bin/env bash
# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
# Fuzzes with libFuzzer (clang and Debian's libclang-rt-dev): load_mesh for each mesh format that
# load_mesh checks before assimp reads it, or reads in a bounded process of its own, and
# parse_scene (tests/fuzz/fuzz_scene.cpp, which also checks the message rules), and the command
# line of measure and voxelize (tests/fuzz/fuzz_cli.cpp, the same rules), and the haptic device
# path's reader (tests/fuzz/fuzz_trajectory.cpp):
#   scripts/fuzz.sh [SECONDS per target, default 240] [TARGET ...] (ply off dae gltf scene cli trajectory)
#   scripts/fuzz.sh --ci   (CI's short run: a fixed number of inputs per target from a fixed seed,
#                           so that it finds the same on every run of the same code)
# The parts not fuzzed come from a build folder, FUZZ_BUILD (default build/release: run
# scripts/setup.sh release first). A crash, a hang (over 10 s) or a broken rule stops the run and
# leaves the input in build/fuzz/; add it as a test case once it is fixed
# (tests/mesh/test_load_mesh.cpp, tests/cli/test_demo.cpp).
set -euo pipefail
cd "$(dirname "$0")/.."
declare -A ci_runs=([scene]=200000 [ply]=20000 [off]=20000 [gltf]=400 [dae]=400 [cli]=100000 [trajectory]=100000)
ci=false
if [ "${1:-}" = --ci ]; then
  ci=true
  shift
  set -- 0 "${!ci_runs[@]}"
fi
seconds=${1:-240}
shift || true
targets=("${@:-ply off dae gltf scene cli trajectory}")
compiler=$(command -v clang++-16 || command -v clang++-14 || command -v clang++)
mkdir -p build/fuzz
release=${FUZZ_BUILD:-build/release}
flags=(-std=c++17 -O1 -g -fsanitize=fuzzer,address -Iinclude -I/usr/include/eigen3)
# the targets build side by side
"$compiler" "${flags[@]}" -Iplugins/mesh/include tests/fuzz/fuzz_load_mesh.cpp plugins/mesh/src/*.cpp \
  "$release"/src/libcubespring.a -lassimp -fopenmp -o build/fuzz/fuzz_load_mesh &
mesh_build=$!
# the scene parser (cubespring::scene_world) is compiled here, instrumented; the parts it calls
# come from the build folder
"$compiler" "${flags[@]}" -DCUBESPRING_DATA_DIR="\"$PWD/data\"" -Iscenes/include -Iscenes/src \
  -Iplugins/bullet/include -Iplugins/render/include -Iplugins/mesh/include $(pkg-config --cflags bullet) \
  tests/fuzz/fuzz_scene.cpp $(ls scenes/src/*.cpp | grep -v scene_frames) "$release"/plugins/bullet/libcubespring_bullet.a \
  "$release"/plugins/render/libcubespring_view.a "$release"/plugins/mesh/libcubespring_mesh.a \
  "$release"/src/libcubespring.a $(pkg-config --libs bullet) -lassimp -fopenmp -o build/fuzz/fuzz_scene
# the command line's parser and its commands' checks, instrumented; the rest from the build folder
"$compiler" "${flags[@]}" -Iapps/common -Iapps/cubespring -Ivalidation/include -Iplugins/mesh/include \
  tests/fuzz/fuzz_cli.cpp apps/common/arguments.cpp apps/common/commands.cpp apps/common/message_text.cpp \
  apps/common/number_checks.cpp \
  apps/cubespring/measure_command.cpp apps/cubespring/voxelize_command.cpp \
  "$release"/validation/libcubespring_validation.a "$release"/plugins/mesh/libcubespring_mesh.a \
  "$release"/src/libcubespring.a -lassimp -fopenmp -o build/fuzz/fuzz_cli &
cli_build=$!
# the device path's reader, instrumented; the core from the build folder
"$compiler" "${flags[@]}" -Iplugins/haptics/include tests/fuzz/fuzz_trajectory.cpp \
  plugins/haptics/src/device_trajectory.cpp "$release"/src/libcubespring.a -fopenmp -o build/fuzz/fuzz_trajectory
wait "$mesh_build"
wait "$cli_build"
for target in ${targets[@]}; do
  corpus=build/fuzz/corpus_$target
  if $ci; then rm -rf "$corpus"; fi  # the same seeds every time
  mkdir -p "$corpus"
  cp tests/fuzz/corpus/"$target"/* "$corpus"/
  if $ci; then
    length=(-runs="${ci_runs[$target]}" -seed=1)
    echo "fuzzing $target: ${ci_runs[$target]} inputs"
  else
    length=(-max_total_time="$seconds")
    echo "fuzzing $target for $seconds s"
  fi
  if [ "$target" = cli ]; then
    # arguments ended by NUL bytes: a command line is short
    (cd build/fuzz && ./fuzz_cli "corpus_$target" "${length[@]}" -timeout=10 -rss_limit_mb=2048 -max_len=1024 \
      -dict=../../tests/fuzz/cli.dict)
    continue
  fi
  if [ "$target" = trajectory ]; then
    # a device path's CSV: its work is per line
    (cd build/fuzz && ./fuzz_trajectory "corpus_$target" "${length[@]}" -timeout=10 -rss_limit_mb=2048 -max_len=4096)
    continue
  fi
  if [ "$target" = scene ]; then
    # a scene file may be up to 16 MB, but the parser's work is in its structure: short inputs
    (cd build/fuzz && ./fuzz_scene "corpus_$target" "${length[@]}" -timeout=10 -rss_limit_mb=2048 \
      -max_len=8192 -dict=../../tests/fuzz/scene.dict)
    continue
  fi
  # leaks inside assimp are known (tests/lsan_suppressions.txt); crashes and hangs are what count
  (cd build/fuzz && ASAN_OPTIONS=detect_leaks=0 FUZZ_EXTENSION=".$target" ./fuzz_load_mesh "corpus_$target" \
    "${length[@]}" -timeout=10 -rss_limit_mb=2048 -max_len=4096 -detect_leaks=0)
done
