// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The subcommands of the cubespring tool: each registers its flags and runs when chosen.
#pragma once

#include <functional>
#include <map>
#include <string>

#include <CLI/CLI.hpp>

namespace cubespring::app {

/// Adds a subcommand to the app; the returned function runs it after parsing and gives the exit code.
using Command = std::function<int()>;
Command add_measure_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_voxelize_command(CLI::App& app);
Command add_bench_voxelize_command(CLI::App& app);
Command add_bench_layout_command(CLI::App& app);
/// Only with Bullet (CUBESPRING_HAS_BULLET).
Command add_bench_bullet_command(CLI::App& app);
/// Only with the Bullet plugin (CUBESPRING_HAS_BULLET_PLUGIN).
Command add_bench_contact_command(CLI::App& app);
/// Only with Bullet and the renderer (CUBESPRING_HAS_DEMO); with no subcommand, main runs it.
Command add_run_command(CLI::App& app);
/// Only with the demo (CUBESPRING_HAS_DEMO): the demo's physics and rendering costs.
Command add_bench_render_command(CLI::App& app);

/// Parses the arguments and runs the subcommand chosen among `commands` (`otherwise` when none
/// is, or the help when that is empty); gives the exit code. Help and version answer on stdout; a
/// parse error is one line naming the argument (exit 2); what escapes a command (memory
/// exhausted, say) is one line and exit 1, never an abort.
int parse_and_run(CLI::App& app, int argc, char** argv, const std::map<std::string, Command>& commands,
                  const Command& otherwise = {});

}  // namespace cubespring::app
