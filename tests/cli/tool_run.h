// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Runs the cubespring tool as a user's script would (CUBESPRING_CLI_PATH), capturing its output.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace cubespring::test {

struct ToolRun {
  int exit_code = -1;
  std::string out;  // stdout, and stderr unless left out
};

inline ToolRun run_tool(const std::string& arguments, bool merge_stderr = true) {
  const std::string command =
      std::string(CUBESPRING_CLI_PATH) + " " + arguments + (merge_stderr ? " 2>&1" : " 2>/dev/null");
  ToolRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) run.out += buffer.data();
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace cubespring::test
