// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "message_text.h"

#include <cstdio>

namespace cubespring::app {
namespace {

std::string escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (byte < 0x20 || byte == 0x7f) {
      char code[8];
      std::snprintf(code, sizeof code, "\\x%02x", byte);
      out += code;
    } else {
      out += c;
    }
  }
  return out;
}

constexpr std::size_t kLongestWord = 80;
constexpr std::size_t kWordShown = 60;

}  // namespace

std::string shown_argument(const std::string& text, std::size_t max_chars) {
  const std::string shown = escaped(text);
  if (shown.size() <= max_chars) return shown;
  return shown.substr(0, max_chars) + "... (" + std::to_string(text.size()) + " characters)";
}

std::string bounded_message(const std::string& message) {
  const std::string text = escaped(message);
  std::string out;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t space = text.find(' ', start);
    const std::size_t end = space == std::string::npos ? text.size() : space;
    const std::string word = text.substr(start, end - start);
    out += word.size() > kLongestWord ? word.substr(0, kWordShown) + "..." : word;
    if (space == std::string::npos) break;
    out += ' ';
    start = space + 1;
  }
  return out;
}

}  // namespace cubespring::app
