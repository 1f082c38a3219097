// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "run_benchmarks.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace cubespring::app {

namespace {

constexpr const char* kBenchmarkCommands[] = {"bench",        "bench-voxelize", "bench-layout",
                                              "bench-bullet", "bench-contact",  "bench-render"};

}  // namespace

bool is_benchmark_command(const char* name) {
  for (const char* command : kBenchmarkCommands) {
    if (std::strcmp(name, command) == 0) return true;
  }
  return false;
}

const char* benchmark_commands_help() {
  return "Benchmarks (each prints a table, or JSON with --json), run by cubespring-bench beside this program:\n"
         "  bench, bench-voxelize, bench-layout, bench-bullet, bench-contact, bench-render\n"
         "  (`cubespring bench --help` lists each one's flags)";
}

int run_benchmarks(int argc, char** argv) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::path self = fs::read_symlink("/proc/self/exe", error);  // where this program is, links resolved
  if (error) self = fs::absolute(argv[0], error);
  const fs::path bench = self.parent_path() / "cubespring-bench";
  if (!fs::is_regular_file(bench, error)) {
    std::cerr << "error: `cubespring " << argv[1] << "` runs the benchmarks' own program, " << bench.string()
              << ", which is not there: cubespring was built without benchmarks (CUBESPRING_BUILD_BENCHMARKS=OFF)"
              << " or installed without it\n";
    return 1;
  }
  std::string path = bench.string();
  std::vector<char*> arguments(argv, argv + argc);
  arguments[0] = path.data();
  arguments.push_back(nullptr);
  ::execv(path.c_str(), arguments.data());
  std::cerr << "error: cannot run " << path << ": " << std::strerror(errno) << "\n";
  return 1;
}

}  // namespace cubespring::app
