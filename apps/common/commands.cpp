// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "commands.h"

#include <exception>
#include <iostream>

#include "message_text.h"

namespace cubespring::app {

std::string parse_error_message(const CLI::ParseError& error) { return bounded_message(error.what()); }

int parse_and_run(CLI::App& app, int argc, char** argv, const std::map<std::string, Command>& commands,
                  const Command& otherwise) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    std::cerr << "error: " << parse_error_message(e) << "\n";
    return 2;
  }
  // the commands report bad input themselves
  try {
    for (const auto& [name, run] : commands) {
      if (app.got_subcommand(name)) return run();
    }
    if (otherwise) return otherwise();
    std::cout << app.help();
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace cubespring::app
