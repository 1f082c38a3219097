// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A file's extension as assimp compares it: lower case, with its dot.
#pragma once

#include <cctype>
#include <filesystem>
#include <string>

namespace cubespring {

inline std::string lowercase_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

}  // namespace cubespring
