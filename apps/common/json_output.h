// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The JSON the commands print with --json.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace cubespring::app {

/// `value` as text, indented by 2. Bytes that are not UTF-8 (a mesh's part names in Latin-1, a
/// path) become U+FFFD: nlohmann's default would throw halfway through the output.
inline std::string json_text(const nlohmann::json& value) {
  return value.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

/// A number of a report that is not finite, and where it is.
struct NonFinite {
  std::string path;  ///< its key path: `measured.young_modulus`, `curve[3].stress`
  double value = 0;
};

/// The first number in `value` that is not finite, if any: a report must never print one (JSON
/// would show it as null, a table as inf or nan).
inline std::optional<NonFinite> first_non_finite(const nlohmann::json& value, const std::string& path = "") {
  if (value.is_number_float() && !std::isfinite(value.get<double>())) return NonFinite{path, value.get<double>()};
  if (value.is_object()) {
    for (auto it = value.begin(); it != value.end(); ++it) {
      if (auto found = first_non_finite(it.value(), path.empty() ? it.key() : path + "." + it.key())) return found;
    }
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      if (auto found = first_non_finite(value[i], path + "[" + std::to_string(i) + "]")) return found;
    }
  }
  return std::nullopt;
}

}  // namespace cubespring::app
