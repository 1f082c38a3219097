// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "off_file.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace cubespring {
namespace {

std::string upper(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return text;
}

bool whole_number(const std::string& word) {
  return !word.empty() && word.size() <= 10 && word.find_first_not_of("0123456789") == std::string::npos &&
         std::stoull(word) <= 0xffffffffULL;  // assimp reads the counts as unsigned int
}

// A word of the file and the line it is on.
struct Word {
  std::string text;
  std::size_t line = 0;
};

Status off_error(const std::string& path, std::size_t line, const std::string& problem) {
  return Status::error(path + ": OFF line " + std::to_string(line) + ": " + problem);
}

}  // namespace

Status check_off_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return {};  // load_mesh reports an unreadable file itself
  const bool named_off = upper(std::filesystem::path(path).extension().string()) == ".OFF";

  // the words before the vertices: the keyword (if any) and the counts
  std::vector<Word> header;
  bool is_off = named_off;
  bool decided = named_off;
  std::size_t counts_line = 0;  // the line the counts end on
  std::size_t lines = 0;
  std::string line;
  while (std::getline(file, line)) {
    ++lines;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.size() > kOffLineLimit) {
      if (!decided) return {};  // no OFF keyword came first: not an OFF file
      std::ostringstream out;
      out << "has " << line.size() << " characters; assimp's OFF reader takes at most " << kOffLineLimit
          << " a line (it overflows its buffer)";
      return off_error(path, lines, out.str());
    }
    if (counts_line != 0) continue;
    std::istringstream words(line.substr(0, line.find('#')));
    std::string word;
    while (words >> word && counts_line == 0) {
      if (!decided) {
        // assimp knows an OFF file by its first word (STCN4nOFF, in that order, each optional)
        decided = true;
        is_off = upper(word).size() >= 3 && upper(word).compare(upper(word).size() - 3, 3, "OFF") == 0;
        if (!is_off) return {};
        header.push_back({word, lines});
        continue;
      }
      header.push_back({word, lines});
      const bool keyword = upper(header.front().text).find("OFF") != std::string::npos;
      const bool has_dimension = keyword && header.front().text.find('n') != std::string::npos;
      if (header.size() == (keyword ? 1u : 0u) + (has_dimension ? 1u : 0u) + 3u) counts_line = lines;
    }
  }
  if (!is_off) return {};
  if (counts_line == 0) {
    return Status::error(path + ": OFF file ends before its vertex, face and edge counts");
  }
  // the three counts are the last three words of the header
  const Word& vertices = header[header.size() - 3];
  const Word& faces = header[header.size() - 2];
  for (const Word* count : {&vertices, &faces}) {
    if (!whole_number(count->text)) {
      return off_error(path, count->line,
                       "'" + count->text.substr(0, 40) + "': expected the vertex, face and edge counts, whole numbers");
    }
  }
  const std::uint64_t needed = std::stoull(vertices.text) + std::stoull(faces.text);
  const std::uint64_t after = lines - counts_line;
  if (needed > after) {
    std::ostringstream out;
    out << "declares " << vertices.text << " vertices and " << faces.text << " faces, a line each, but only " << after
        << " lines follow";
    return off_error(path, counts_line, out.str());
  }
  return {};
}

}  // namespace cubespring
