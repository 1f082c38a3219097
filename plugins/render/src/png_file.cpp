// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// PNG files through libpng's simplified API: it keeps libpng's setjmp/longjmp error handling
// inside libpng, where it cannot jump over C++ destructors.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include <png.h>

#include "cubespring/render/image.h"

namespace cubespring {

Status write_png(const Image& image, const std::string& path) {
  // the pixels must match the stated size before libpng reads them
  const std::size_t expected = 3 * static_cast<std::size_t>(image.width > 0 ? image.width : 0) *
                               static_cast<std::size_t>(image.height > 0 ? image.height : 0);
  if (image.width < 1 || image.height < 1 || image.rgb.size() != expected) {
    return Status::error(path + ": cannot write an image of " + std::to_string(image.width) + " x " +
                         std::to_string(image.height) + " pixels with " + std::to_string(image.rgb.size()) +
                         " bytes of RGB (need width, height >= 1 and 3 bytes a pixel)");
  }

  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    return Status::error(path + ": cannot open for writing: " + std::strerror(errno));
  }

  // no time or text chunks are written and libpng's compression settings are fixed, so equal
  // pixels give equal bytes for one libpng and zlib build. Its fast settings (zlib level 3, no
  // filters): a demo frame of 1280x720 took 44 ms at the default ones (level 6, adaptive
  // filters), more than drawing it (31 ms), and takes 7 ms, its file 290 kB instead of 175 kB.
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
#ifdef PNG_IMAGE_FLAG_FAST  // libpng 1.6.22 on (Debian 12 has 1.6.39); older ones write as before
  png.flags = PNG_IMAGE_FLAG_FAST;
#endif
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  const int written =
      png_image_write_to_stdio(&png, file, 0, image.rgb.data(), static_cast<png_int_32>(3 * image.width), nullptr);
  const std::string png_message = png.message;
  png_image_free(&png);
  const int closed = std::fclose(file);
  if (written == 0 || closed != 0) {
    const std::string reason = written == 0 ? png_message : std::string(std::strerror(errno));
    std::remove(path.c_str());  // leave no truncated file behind
    return Status::error(path + ": cannot write PNG: " + reason);
  }
  return {};
}

Result<Image> read_png(const std::string& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (png_image_begin_read_from_file(&png, path.c_str()) == 0) {
    const std::string message = png.message;
    png_image_free(&png);
    return Status::error(path + ": cannot read PNG: " + message);
  }

  // 8-bit RGB whatever the file holds; a zeroed buffer composites any alpha onto black
  png.format = PNG_FORMAT_RGB;
  Image image;
  image.width = static_cast<int>(png.width);
  image.height = static_cast<int>(png.height);
  image.rgb.assign(PNG_IMAGE_SIZE(png), 0);
  if (png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr) == 0) {
    const std::string message = png.message;
    png_image_free(&png);
    return Status::error(path + ": cannot read PNG: " + message);
  }
  return image;
}

}  // namespace cubespring
