// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "number_checks.h"

#include <cmath>
#include <cstdlib>
#include <string>

#include "message_text.h"

namespace cubespring::app {
namespace {

// A number that `accept` takes, else the error "'TEXT' is not <what>".
CLI::Validator number_check(bool (*accept)(double), const std::string& what, const std::string& description,
                            const std::string& name) {
  return CLI::Validator(
      [accept, what](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size()) return "'" + shown_argument(text) + "' is not a number";
        if (!accept(value)) return "'" + shown_argument(text) + "' is not " + what;
        return {};
      },
      description, name);
}

}  // namespace

CLI::Validator finite_positive_number() {
  return number_check([](double value) { return std::isfinite(value) && value > 0.0; }, "a finite number > 0",
                      "NUMBER > 0", "FINITE_POSITIVE");
}

CLI::Validator finite_number() {
  return number_check([](double value) { return std::isfinite(value); }, "a finite number", "NUMBER", "FINITE");
}

CLI::Validator byte_count() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
          return "'" + shown_argument(text) + "' is not a whole number of bytes >= 0";
        }
        return {};
      },
      "BYTES", "BYTE_COUNT");
}

CLI::Validator fraction_number() {
  return number_check([](double value) { return value > 0.0 && value <= 1.0; }, "in (0, 1]", "NUMBER in (0, 1]",
                      "FRACTION");
}

}  // namespace cubespring::app
