// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "message_text.h"

#include <cstdio>

namespace cubespring::app {
namespace {

// One byte as a message shows it: a control character escaped, anything else as it is.
std::string shown_byte(char c) {
  const auto byte = static_cast<unsigned char>(c);
  if (c == '\n') return "\\n";
  if (c == '\t') return "\\t";
  if (c == '\r') return "\\r";
  if (byte < 0x20 || byte == 0x7f) {
    char code[8];
    std::snprintf(code, sizeof code, "\\x%02x", byte);
    return code;
  }
  return std::string(1, c);
}

bool continues_a_character(char c) { return (static_cast<unsigned char>(c) & 0xc0) == 0x80; }  // UTF-8

// `text` shown, cut before it shows more than max_chars (never inside an escape or a character),
// with "..." and, when `count`, the text's length in characters of the input.
std::string shown_cut(const std::string& text, std::size_t max_chars, bool count) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const std::string piece = shown_byte(text[i]);
    if (out.size() + piece.size() > max_chars && !continues_a_character(text[i])) {
      return out + "..." + (count ? " (" + std::to_string(text.size()) + " characters)" : "");
    }
    out += piece;
  }
  return out;
}

constexpr std::size_t kLongestWord = 80;
constexpr std::size_t kWordShown = 60;
constexpr std::size_t kLongestMessage = 300;

}  // namespace

std::string shown_argument(const std::string& text, std::size_t max_chars) { return shown_cut(text, max_chars, true); }

std::string bounded_message(const std::string& message) {
  std::string out;
  std::size_t start = 0;
  while (true) {
    const std::size_t space = message.find(' ', start);
    const std::size_t end = space == std::string::npos ? message.size() : space;
    const std::string word = message.substr(start, end - start);
    const std::string shown = shown_cut(word, word.size() > kLongestWord ? kWordShown : std::string::npos, false);
    // a message that lists many arguments (CLI11's "not expected: ...") is cut as a whole too
    if (out.size() + shown.size() > kLongestMessage) return out + "...";
    out += shown;
    if (space == std::string::npos) return out;
    out += ' ';
    start = space + 1;
  }
}

}  // namespace cubespring::app
