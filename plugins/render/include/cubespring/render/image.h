// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cubespring/result.h"

namespace cubespring {

/// An 8-bit sRGB picture, rows from the top.
struct Image {
  int width = 0;                  ///< [pixels]
  int height = 0;                 ///< [pixels]
  std::vector<std::uint8_t> rgb;  ///< (height x width x 3) red, green, blue of each pixel, row-major

  /// The three channels of pixel (x, y), x from the left, y from the top; no bounds check.
  const std::uint8_t* pixel(int x, int y) const {
    return &rgb[3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x))];
  }
};

/// Writes an 8-bit RGB PNG. The bytes depend only on the pixels (no time or text chunks, fixed
/// compression level and filters), so two equal frames give two equal files. Errors name the path.
Status write_png(const Image& image, const std::string& path);

/// Reads any PNG as 8-bit RGB (alpha dropped, palettes expanded). Errors name the path.
Result<Image> read_png(const std::string& path);

}  // namespace cubespring
