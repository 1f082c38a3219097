// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// libFuzzer target: the command line of `cubespring measure` and `voxelize`, as main.cpp
// builds it (`run`'s flags are CLI11's ranges alone; its scene is fuzz_scene's). The input is
// the arguments, each ended by a NUL byte (as argv's are, so that an argument may hold a line
// break); they are parsed, and the chosen command's check stage (commands.h: what it reads of its
// flags before it starts its work, no file) runs alone. Beyond crashes, hangs and sanitizer
// faults, it stops on a broken message rule: an error is at most two lines and 600 characters
// (an argument echoed whole breaks it), and a check's error names a flag. scripts/fuzz.sh runs it.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "commands.h"

namespace {

[[noreturn]] void fail(const char* rule, const std::string& detail) {
  std::fprintf(stderr, "fuzz_cli: %s: %s\n", rule, detail.c_str());
  std::abort();
}

void check_message(const std::string& message) {
  if (message.empty()) fail("an error without a message", "");
  std::size_t lines = 1;
  for (const char c : message) lines += c == '\n' ? 1 : 0;
  if (lines > 2 || message.size() > 600) fail("the error is longer than two short lines", message);
}

constexpr std::size_t kMaxArguments = 64;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> arguments{"cubespring"};
  std::string current;
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == '\0') {
      arguments.push_back(current);
      current.clear();
    } else {
      current.push_back(static_cast<char>(data[i]));
    }
  }
  if (!current.empty()) arguments.push_back(current);
  if (arguments.size() > kMaxArguments) return 0;
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());

  CLI::App app{"cubespring"};
  app.set_version_flag("--version", "cubespring 0.1.0");
  const cubespring::app::CheckedCommand measure = cubespring::app::add_checked_measure_command(app);
  const cubespring::app::CheckedCommand voxelize = cubespring::app::add_checked_voxelize_command(app);
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::CallForHelp&) {
    return 0;
  } catch (const CLI::CallForVersion&) {
    return 0;
  } catch (const CLI::ParseError& e) {
    check_message(cubespring::app::parse_error_message(e));  // what parse_and_run prints
    return 0;
  }
  for (const auto& [name, command] : {std::pair{"measure", &measure}, std::pair{"voxelize", &voxelize}}) {
    if (!app.got_subcommand(name)) continue;
    const cubespring::Status checked = command->check();
    if (checked.ok()) continue;
    check_message(checked.message());
    if (checked.message().find("--") == std::string::npos) fail("a check's error names no flag", checked.message());
  }
  return 0;
}
