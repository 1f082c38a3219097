// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "ply_file.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "file_extension.h"

namespace cubespring {
namespace {

// Bytes of each scalar type in a binary PLY file (both spellings: the original and PLY 1.0's).
const std::map<std::string, std::uint64_t>& scalar_sizes() {
  static const std::map<std::string, std::uint64_t> sizes{{"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},
                                                          {"short", 2}, {"ushort", 2},  {"int16", 2},  {"uint16", 2},
                                                          {"int", 4},   {"uint", 4},    {"int32", 4},  {"uint32", 4},
                                                          {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  return sizes;
}

struct Property {
  bool list = false;
  std::uint64_t size = 0;       // a scalar's bytes, or a list count's
  std::uint64_t item_size = 0;  // a list item's bytes
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  int line = 0;
  std::uint64_t binary_bytes = 0;  // the least bytes one element takes in binary
  std::uint64_t properties = 0;
  std::vector<Property> layout;
};

// A list's count as stored in `size` bytes of binary, little- or big-endian.
std::uint64_t read_count(const std::string& body, std::uint64_t at, std::uint64_t size, bool big_endian) {
  std::uint64_t value = 0;
  for (std::uint64_t i = 0; i < size; ++i) {
    const std::uint64_t byte =
        static_cast<unsigned char>(body[static_cast<std::size_t>(at + (big_endian ? i : size - 1 - i))]);
    value = (value << 8) | byte;
  }
  return value;
}

// Walks the body as the header lays it out; the element it runs out in, or -1 when it holds
// every element. Binary: each scalar its bytes, each list its count's bytes and count items.
// ASCII: a word each scalar, a list its count word and count words.
long first_short_element(const std::vector<Element>& elements, const std::string& body, bool binary, bool big_endian) {
  std::istringstream words(binary ? std::string() : body);
  std::uint64_t at = 0;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (std::uint64_t n = 0; n < elements[e].count; ++n) {
      for (const Property& property : elements[e].layout) {
        if (binary) {
          if (at + property.size > body.size()) return static_cast<long>(e);
          const std::uint64_t items = property.list ? read_count(body, at, property.size, big_endian) : 0;
          at += property.size;
          if (items > (body.size() - at) / std::max<std::uint64_t>(property.item_size, 1)) return static_cast<long>(e);
          at += items * property.item_size;
          continue;
        }
        std::string word;
        if (!(words >> word)) return static_cast<long>(e);
        if (!property.list) continue;
        const bool whole =
            !word.empty() && word.size() <= 9 && word.find_first_not_of("0123456789") == std::string::npos;
        if (!whole) return static_cast<long>(e);
        for (std::uint64_t i = std::stoull(word); i > 0; --i) {
          if (!(words >> word)) return static_cast<long>(e);
        }
      }
    }
  }
  return -1;
}

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

Status check_ply_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return {};  // load_mesh reports an unreadable file itself
  std::string head(kPlyHeaderLimit, '\0');
  file.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(file.gcount()));
  // assimp takes a file for PLY by its extension, or by its first bytes
  if (lowercase_extension(path) != ".ply" && head.compare(0, 3, "ply") != 0) return {};
  if (head.compare(0, 3, "ply") != 0 || head.size() < 4 || (head[3] != '\n' && head[3] != '\r')) {
    return header_error(path, 1, "a PLY file begins with the line 'ply'");
  }
  std::error_code size_error;
  const std::uint64_t file_size = std::filesystem::file_size(path, size_error);
  if (size_error) return Status::error(path + ": cannot read its size: " + size_error.message());

  std::vector<Element> elements;
  bool binary = false;
  bool big_endian = false;
  bool has_format = false;
  std::size_t start = 0;
  for (int line_number = 1;; ++line_number) {
    const std::size_t end = head.find('\n', start);
    if (end == std::string::npos) {
      std::ostringstream out;
      out << path << ": PLY header has no 'end_header' line in its first " << head.size() << " bytes";
      if (file_size > head.size())
        out << " (of " << file_size << "; a header may take at most " << kPlyHeaderLimit << ")";
      out << ": the file is cut short or not a PLY file";
      return Status::error(out.str());
    }
    std::string line = head.substr(start, end - start);
    start = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    // a header is text: words apart by spaces or tabs (a vertical tab after 'end_header' hid it
    // from assimp, which then read forever)
    if (std::any_of(line.begin(), line.end(), [](char c) { return (c < 32 && c != '\t') || c > 126; })) {
      return header_error(path, line_number,
                          "'" + shown(line) + "' holds a byte that is not text (a header line is printable ASCII)");
    }
    while (!line.empty() && (line.back() == ' ' || line.back() == '\t')) line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (line_number == 1 || keyword == "comment" || keyword == "obj_info") continue;
    if (line == "end_header") {
      if (!has_format) return header_error(path, line_number, "no 'format' line before 'end_header'");
      // the least the declared elements take, against what follows the header
      const std::uint64_t body_size = file_size - start;
      for (const Element& element : elements) {
        const std::uint64_t each = binary ? element.binary_bytes : 2 * element.properties;
        const std::uint64_t least = saturating_multiply_add(element.count, each, 0);
        if (least > body_size) {
          std::ostringstream out;
          out << "declares " << element.count << " '" << element.name << "' elements, at least " << least
              << " bytes, but only " << body_size << " bytes follow the header";
          return header_error(path, element.line, out.str());
        }
      }
      // then the elements themselves, as the header lays them out: assimp reads past the end of
      // a body that does not hold them
      file.clear();
      file.seekg(static_cast<std::streamoff>(start));
      const std::string body(std::istreambuf_iterator<char>(file), {});
      const long short_element = first_short_element(elements, body, binary, big_endian);
      if (short_element >= 0) {
        const Element& element = elements[static_cast<std::size_t>(short_element)];
        return header_error(path, element.line,
                            "the file ends inside its '" + element.name + "' elements (their " +
                                std::to_string(element.count) + " as the header lays them out, lists included)");
      }
      return {};
    }
    if (keyword == "format") {
      std::string kind, version;
      words >> kind >> version;
      if (has_format || !elements.empty()) {
        return header_error(path, line_number, "a second 'format' line, or one after an element");
      }
      if ((kind != "ascii" && kind != "binary_little_endian" && kind != "binary_big_endian") || version != "1.0") {
        return header_error(
            path, line_number,
            "'" + shown(line) + "': expected 'format ascii 1.0' (or binary_little_endian, binary_big_endian)");
      }
      binary = kind != "ascii";
      big_endian = kind == "binary_big_endian";
      has_format = true;
      continue;
    }
    if (keyword == "element") {
      Element element;
      std::string count;
      words >> element.name >> count;
      element.line = line_number;
      const bool whole =
          !count.empty() && count.size() <= 19 && count.find_first_not_of("0123456789") == std::string::npos;
      if (element.name.empty() || !whole) {
        return header_error(path, line_number,
                            "'" + shown(line) + "': expected 'element NAME COUNT', COUNT a whole number");
      }
      element.count = std::stoull(count);
      if (std::any_of(elements.begin(), elements.end(), [&](const Element& e) { return e.name == element.name; })) {
        return header_error(path, line_number, "a second element '" + shown(element.name) + "'");
      }
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
                            "'" + shown(line) +
                                "': expected 'property TYPE NAME' or 'property list TYPE TYPE NAME', TYPE one "
                                "of char, uchar, short, ushort, int, uint, float, double (or int8 .. float64)");
      }
      elements.back().binary_bytes += size->second;
      ++elements.back().properties;
      elements.back().layout.push_back({list, size->second, list ? scalar_sizes().at(item_type) : 0});
      continue;
    }
    return header_error(path, line_number,
                        "'" + shown(line) +
                            "' is not a PLY header line (expected format, element, property, comment, obj_info or "
                            "end_header)");
  }
}

}  // namespace cubespring
