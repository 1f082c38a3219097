// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A file's extension as assimp compares it: lower case, with its dot.
#pragma once

#include <cctype>
#include <filesystem>
#include <string>

namespace cubespring {

inline std::string lowercase_extension(const std::string& path) {
  // from the last dot of the file's name, as assimp takes it: a file named ".obj" is an OBJ file
  // (std::filesystem calls that name a stem without an extension)
  const std::string name = std::filesystem::path(path).filename().string();
  const std::size_t dot = name.rfind('.');
  std::string extension = dot == std::string::npos ? std::string() : name.substr(dot);
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

}  // namespace cubespring
