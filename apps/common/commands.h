// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The subcommands of the cubespring tool: each registers its flags and runs when chosen.
#pragma once

#include <functional>
#include <map>
#include <string>

#include <CLI/CLI.hpp>

#include "cubespring/result.h"

namespace cubespring::app {

/// Adds a subcommand to the app; the returned function runs it after parsing and gives the exit code.
using Command = std::function<int()>;
/// A subcommand in two stages: `check` reads the parsed flags as the command does before it
/// starts its work (it reads no file and runs nothing) and gives the message of the first one at
/// fault, which `run` prints after "error: " with exit 2; `run` does the whole, the check
/// included. The command line's fuzz target (tests/fuzz/fuzz_cli.cpp) calls `check` alone.
struct CheckedCommand {
  std::function<Status()> check;
  Command run;
};
CheckedCommand add_checked_measure_command(CLI::App& app);
CheckedCommand add_checked_voxelize_command(CLI::App& app);
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
/// Only with the demo (CUBESPRING_HAS_DEMO) and the haptics part: a recorded device path
/// played against a scene through a virtual coupling.
Command add_haptic_replay_command(CLI::App& app);
/// Only with the demo (CUBESPRING_HAS_DEMO): the demo's physics and rendering costs.
Command add_bench_render_command(CLI::App& app);

/// What parse_and_run prints after "error: " for a parse error: CLI11's message, whose quoted
/// arguments are cut short and kept on its line (message_text.h).
std::string parse_error_message(const CLI::ParseError& error);

/// Parses the arguments and runs the subcommand chosen among `commands` (`otherwise` when none
/// is, or the help when that is empty); gives the exit code. Help and version answer on stdout; a
/// parse error is one line naming the argument (exit 2); what escapes a command (memory
/// exhausted, say) is one line and exit 1, never an abort.
int parse_and_run(CLI::App& app, int argc, char** argv, const std::map<std::string, Command>& commands,
                  const Command& otherwise = {});

}  // namespace cubespring::app
