// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// `cubespring bench...`: the benchmarks are their own program, cubespring-bench, built and
// installed beside this one; their subcommands are handed to it unchanged.
#pragma once

namespace cubespring::app {

/// Whether `name` is one of the benchmarks' subcommands (bench, bench-voxelize, ...).
bool is_benchmark_command(const char* name);
/// The names, for the help's footer.
const char* benchmark_commands_help();

/// Replaces this process by cubespring-bench with the same arguments; returns (1, having said
/// why on stderr) only when that program is not beside this one or cannot be run.
int run_benchmarks(int argc, char** argv);

}  // namespace cubespring::app
