// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "number_checks.h"

#include <cmath>
#include <cstdlib>
#include <string>

namespace cubespring::app {

CLI::Validator finite_positive_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size()) return "'" + text + "' is not a number";
        if (!std::isfinite(value) || !(value > 0.0)) return "'" + text + "' is not a finite number > 0";
        return {};
      },
      "NUMBER > 0", "FINITE_POSITIVE");
}

CLI::Validator fraction_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size()) return "'" + text + "' is not a number";
        if (!(value > 0.0 && value <= 1.0)) return "'" + text + "' is not in (0, 1]";
        return {};
      },
      "NUMBER in (0, 1]", "FRACTION");
}

}  // namespace cubespring::app
