// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The JSON the commands print with --json.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace cubespring::app {

/// `value` as text, indented by 2. Bytes that are not UTF-8 (a mesh's part names in Latin-1, a
/// path) become U+FFFD: nlohmann's default would throw halfway through the output.
inline std::string json_text(const nlohmann::json& value) {
  return value.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace cubespring::app
