// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "ply_header.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

namespace cubespring {
namespace {

// Bytes of each scalar type in a binary PLY file (both spellings: the original and PLY 1.0's).
const std::map<std::string, std::uint64_t>& scalar_sizes() {
  static const std::map<std::string, std::uint64_t> sizes{
      {"char", 1},   {"uchar", 1},  {"int8", 1},    {"uint8", 1},   {"short", 2},   {"ushort", 2},
      {"int16", 2},  {"uint16", 2}, {"int", 4},     {"uint", 4},    {"int32", 4},   {"uint32", 4},
      {"float", 4},  {"float32", 4}, {"double", 8}, {"float64", 8}};
  return sizes;
}

struct Element {
  std::string name;
  std::uint64_t count = 0;
  int line = 0;
  std::uint64_t binary_bytes = 0;  // the least bytes one element takes in binary
  std::uint64_t properties = 0;
};

// a * b + c, saturating at the largest value: a corrupt count must not wrap round to a small one
std::uint64_t saturating_multiply_add(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  if (b != 0 && a > (kMax - c) / b) return kMax;
  return a * b + c;
}

// A header line as a message shows it: at most 80 characters, bytes that are not printable ASCII
// (a binary body read as header) as '?'.
std::string shown(const std::string& line) {
  std::string text = line.substr(0, 80);
  for (char& c : text) {
    if (c < 32 || c > 126) c = '?';
  }
  return line.size() > 80 ? text + "..." : text;
}

Status header_error(const std::string& path, int line, const std::string& problem) {
  return Status::error(path + ": PLY header line " + std::to_string(line) + ": " + problem);
}

}  // namespace

Status check_ply_header(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return {};  // load_mesh reports an unreadable file itself
  std::string head(kPlyHeaderLimit, '\0');
  file.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(file.gcount()));
  if (head.compare(0, 3, "ply") != 0 || head.size() < 4 || (head[3] != '\n' && head[3] != '\r')) return {};
  std::error_code size_error;
  const std::uint64_t file_size = std::filesystem::file_size(path, size_error);
  if (size_error) return Status::error(path + ": cannot read its size: " + size_error.message());

  std::vector<Element> elements;
  bool binary = false;
  bool has_format = false;
  std::size_t start = 0;
  for (int line_number = 1;; ++line_number) {
    const std::size_t end = head.find('\n', start);
    if (end == std::string::npos) {
      std::ostringstream out;
      out << path << ": PLY header has no 'end_header' line in its first " << head.size() << " bytes";
      if (file_size > head.size()) out << " (of " << file_size << "; a header may take at most " << kPlyHeaderLimit << ")";
      out << ": the file is cut short or not a PLY file";
      return Status::error(out.str());
    }
    std::string line = head.substr(start, end - start);
    start = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (line_number == 1 || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      if (!has_format) return header_error(path, line_number, "no 'format' line before 'end_header'");
      // the least the declared elements take, against what follows the header
      const std::uint64_t body = file_size - start;
      for (const Element& element : elements) {
        const std::uint64_t each = binary ? element.binary_bytes : 2 * element.properties;
        const std::uint64_t least = saturating_multiply_add(element.count, each, 0);
        if (least > body) {
          std::ostringstream out;
          out << "declares " << element.count << " '" << element.name << "' elements, at least " << least
              << " bytes, but only " << body << " bytes follow the header";
          return header_error(path, element.line, out.str());
        }
      }
      return {};
    }
    if (keyword == "format") {
      std::string kind;
      words >> kind;
      if (kind != "ascii" && kind != "binary_little_endian" && kind != "binary_big_endian") {
        return header_error(path, line_number,
                            "format '" + shown(kind) + "': expected ascii, binary_little_endian or binary_big_endian");
      }
      binary = kind != "ascii";
      has_format = true;
      continue;
    }
    if (keyword == "element") {
      Element element;
      std::string count;
      words >> element.name >> count;
      element.line = line_number;
      const bool whole = !count.empty() && count.size() <= 19 && count.find_first_not_of("0123456789") == std::string::npos;
      if (element.name.empty() || !whole) {
        return header_error(path, line_number,
                            "'" + shown(line) + "': expected 'element NAME COUNT', COUNT a whole number");
      }
      element.count = std::stoull(count);
      elements.push_back(element);
      continue;
    }
    if (keyword == "property") {
      if (elements.empty()) return header_error(path, line_number, "a property before any element");
      std::string type;
      words >> type;
      const bool list = type == "list";
      if (list) words >> type;  // the count's type: a list takes at least its count
      std::string item_type = type;
      if (list) words >> item_type;
      std::string name;
      words >> name;
      const auto size = scalar_sizes().find(type);
      if (size == scalar_sizes().end() || scalar_sizes().count(item_type) == 0 || name.empty()) {
        return header_error(path, line_number,
                            "'" + shown(line) + "': expected 'property TYPE NAME' or 'property list TYPE TYPE NAME', TYPE one "
                            "of char, uchar, short, ushort, int, uint, float, double (or int8 .. float64)");
      }
      elements.back().binary_bytes += size->second;
      ++elements.back().properties;
      continue;
    }
    return header_error(path, line_number,
                        "'" + shown(line) +
                            "' is not a PLY header line (expected format, element, property, comment, obj_info or "
                            "end_header)");
  }
}

}  // namespace cubespring
