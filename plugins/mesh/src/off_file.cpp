// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "off_file.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>

#include "file_extension.h"

namespace cubespring {
namespace {

// The file read as assimp's OFF reader reads it (assimp/ParsingUtils.h, OFFLoader.cpp): a cursor
// over the text, which ends at its first NUL as assimp's buffer does.
class OffText {
 public:
  explicit OffText(std::string text) : text_(std::move(text)) { text_.push_back('\0'); }

  char at() const { return text_[pos_]; }
  bool ended() const { return at() == '\0'; }
  // the line the cursor is on [1-based]
  std::size_t line() const { return line_; }

  void skip_spaces() {
    while (at() == ' ' || at() == '\t') step();
  }
  void skip_spaces_and_line_ends() {
    while (at() == ' ' || at() == '\t' || at() == '\r' || at() == '\n') step();
  }
  void skip_line() {
    while (at() != '\r' && at() != '\n' && at() != '\0') step();
    while (at() == '\r' || at() == '\n') step();
  }
  // to the next word, over comment lines
  void next_token() {
    skip_spaces_and_line_ends();
    while (at() == '#' || at() == '\n' || at() == '\r') {
      skip_line();
      skip_spaces_and_line_ends();
    }
  }
  bool starts_with(const char* word) const {
    return text_.compare(pos_, std::char_traits<char>::length(word), word) == 0;
  }
  void advance(std::size_t count) {
    for (std::size_t i = 0; i < count; ++i) step();
  }
  // digits as an unsigned int, wrapping as assimp's strtoul10 does; `digits` says how many
  std::uint32_t number(int& digits) {
    std::uint32_t value = 0;
    digits = 0;
    while (at() >= '0' && at() <= '9') {
      value = value * 10u + static_cast<std::uint32_t>(at() - '0');
      step();
      ++digits;
    }
    return value;
  }
  // the next line (to \r, \n, \f or NUL), then past every line end but NUL; false at the end
  bool next_line(std::string& line) {
    if (ended()) return false;
    const std::size_t start = pos_;
    while (at() != '\r' && at() != '\n' && at() != '\f' && at() != '\0') step();
    line = text_.substr(start, pos_ - start);
    while (at() == '\r' || at() == '\n' || at() == '\f') step();
    return true;
  }

 private:
  void step() {
    if (at() == '\n') ++line_;
    ++pos_;
  }

  std::string text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

Status off_error(const std::string& path, std::size_t line, const std::string& problem) {
  return Status::error(path + ": OFF line " + std::to_string(line) + ": " + problem);
}

// Whether the line is too long for assimp's line buffer, as an error.
Status check_length(const std::string& path, const std::string& line, std::size_t line_number) {
  if (line.size() <= kOffLineLimit) return {};
  std::ostringstream out;
  out << "has " << line.size() << " characters; assimp's OFF reader takes at most " << kOffLineLimit
      << " a line (it overflows its buffer)";
  return off_error(path, line_number, out.str());
}

}  // namespace

Status check_off_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return {};  // load_mesh reports an unreadable file itself
  std::string head(3, '\0');
  file.read(head.data(), 3);
  // assimp takes a file for OFF by its extension, or by the word 'off' at its start
  const bool named = lowercase_extension(path) == ".off";
  std::string lowered = head;
  for (char& c : lowered) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (!named && lowered != "off") return {};
  file.seekg(0);
  OffText text(std::string(std::istreambuf_iterator<char>(file), {}));

  // the header as the reader parses it: [ST][C][N][4][n]OFF, a dimension after n, three counts
  text.next_token();
  bool dimension = false;
  if (text.starts_with("ST")) text.advance(2);
  if (text.starts_with("C")) text.advance(1);
  if (text.starts_with("N")) text.advance(1);
  if (text.starts_with("4")) text.advance(1);
  if (text.starts_with("n")) {
    dimension = true;
    text.advance(1);
  }
  if (text.starts_with("OFF")) text.advance(3);
  text.next_token();
  int digits = 0;
  if (dimension) {
    text.number(digits);
    text.next_token();
  }
  text.next_token();
  const std::size_t counts_line = text.line();
  int vertex_digits = 0, face_digits = 0;
  const std::uint32_t vertices = text.number(vertex_digits);
  text.next_token();
  const std::uint32_t faces = text.number(face_digits);
  text.next_token();
  text.number(digits);  // edges
  text.next_token();
  if (vertex_digits == 0 || face_digits == 0) {
    return off_error(path, counts_line, "expected the vertex, face and edge counts, whole numbers");
  }
  if (vertices == 0 || faces == 0) return {};  // assimp refuses these itself

  // the vertex lines, then the face lines; assimp allocates both before it reads a line
  std::string line;
  std::size_t read = 0;
  const std::size_t body_line = text.line();
  for (; read < static_cast<std::size_t>(vertices) + faces; ++read) {
    const std::size_t line_number = text.line();
    if (!text.next_line(line)) break;
    if (Status length = check_length(path, line, line_number); !length.ok()) return length;
    if (read < vertices) continue;
    // a face: its corner count, 1 to 9 as assimp reads faces (13 crashed it), then as many
    // vertex indices below the vertex count
    const std::size_t face = read - vertices;
    OffText words(line);
    words.skip_spaces();
    const std::uint32_t corners = words.number(digits);
    if (corners < 1 || corners > 9) {
      return off_error(path, line_number,
                       "face " + std::to_string(face) + " has " + std::to_string(corners) +
                           " corners: expected 1 to 9 vertex indices after the count");
    }
    for (std::uint32_t k = 0; k < corners; ++k) {
      words.skip_spaces();
      const std::uint32_t index = words.number(digits);
      if (digits == 0 || index >= vertices) {
        return off_error(
            path, line_number,
            "face " + std::to_string(face) + ": corner " + std::to_string(k) +
                (digits == 0 ? std::string(" is missing or not a number") : " is vertex " + std::to_string(index)) +
                ": expected a vertex index below " + std::to_string(vertices));
      }
    }
  }
  if (read < static_cast<std::size_t>(vertices) + faces) {
    std::ostringstream out;
    out << "declares " << vertices << " vertices and " << faces << " faces, a line each from line " << body_line
        << ", but the file has only " << read << " lines of them";
    return off_error(path, counts_line, out.str());
  }
  return {};
}

}  // namespace cubespring
