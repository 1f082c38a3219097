// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// JSON read with the line of every key, so that errors in a scene file can point at the line.
#pragma once

#include <cstddef>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "cubespring/result.h"

namespace cubespring::scene {

/// A parsed JSON document and where its values are in the text.
/// How deep objects and arrays may nest in a document parse_json_with_lines() takes.
inline constexpr std::size_t kMaxJsonDepth = 64;

struct JsonWithLines {
  nlohmann::json value;
  /// 1-based line of each value by its JSON pointer ("/organ/scale", "/tools/0/keyframes/1"):
  /// the line of its key inside an object, the line where it starts inside an array.
  std::map<std::string, int> lines;

  /// The line of `pointer`, or of the nearest enclosing value that has one (1 at worst).
  int line_of(const std::string& pointer) const;
};

/// Parses JSON text; `//` and `/* */` comments are allowed. Syntax errors and duplicate keys are
/// errors of the form "SOURCE:LINE: message".
Result<JsonWithLines> parse_json_with_lines(const std::string& text, const std::string& source);

/// `text` in double quotes for a message: control bytes escaped (\xNN), and
/// cut in the middle to at most `max_chars` of it ("start...end"), so that a key or a value
/// of a broken file cannot make a message longer than a line.
std::string quote_for_message(const std::string& text, std::size_t max_chars = 60);

/// `parent` + "/" + `key`, with '~' and '/' escaped as JSON pointers require.
std::string child_pointer(const std::string& parent, const std::string& key);

}  // namespace cubespring::scene
