// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/render/force_plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "bitmap_font.h"  // the same letters as the frames' legend

namespace cubespring {
namespace {

using Rgb = std::array<std::uint8_t, 3>;

const Rgb kInk{30, 30, 30};
const Rgb kGrid{225, 225, 225};
// Okabe-Ito colours: told apart by colour-blind readers too
const std::array<Rgb, 6> kLines{
    {{0, 114, 178}, {213, 94, 0}, {0, 158, 115}, {204, 121, 167}, {230, 159, 0}, {86, 180, 233}}};

class Canvas {
 public:
  Canvas(int width, int height) {
    image_.width = width;
    image_.height = height;
    image_.rgb.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3, 255);
  }

  void dot(int x, int y, const Rgb& colour) {
    if (x < 0 || y < 0 || x >= image_.width || y >= image_.height) return;
    std::uint8_t* p = &image_.rgb[3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(image_.width) +
                                       static_cast<std::size_t>(x))];
    std::copy(colour.begin(), colour.end(), p);
  }

  void rect(int x, int y, int w, int h, const Rgb& colour) {
    for (int j = y; j < y + h; ++j) {
      for (int i = x; i < x + w; ++i) dot(i, j, colour);
    }
  }

  // a line `thickness` pixels wide, stepped one pixel at a time along its longer axis
  void line(double x0, double y0, double x1, double y1, const Rgb& colour, int thickness) {
    const int steps = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))));
    for (int s = 0; s <= steps; ++s) {
      const double f = static_cast<double>(s) / steps;
      const int x = static_cast<int>(std::lround(x0 + f * (x1 - x0)));
      const int y = static_cast<int>(std::lround(y0 + f * (y1 - y0)));
      rect(x - thickness / 2, y - thickness / 2, thickness, thickness, colour);
    }
  }

  static int text_width(const std::string& text, int scale) {
    return text.empty() ? 0 : (static_cast<int>(text.size()) * kGlyphAdvance - 1) * scale;
  }

  void text(const std::string& text, int x, int y, int scale, const Rgb& colour) {
    for (std::size_t i = 0; i < text.size(); ++i) {
      const int left = x + static_cast<int>(i) * kGlyphAdvance * scale;
      for (int row = 0; row < kGlyphHeight; ++row) {
        for (int column = 0; column < kGlyphWidth; ++column) {
          if (glyph_pixel(text[i], column, row)) rect(left + column * scale, y + row * scale, scale, scale, colour);
        }
      }
    }
  }

  Image take() { return std::move(image_); }

 private:
  Image image_;
};

// 1, 2 or 5 times a power of ten: about `count` steps over [0, high]
double tick_step(double high, int count) {
  const double raw = high / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double nice : {1.0, 2.0, 5.0, 10.0}) {
    if (nice * power >= raw) return nice * power;
  }
  return 10.0 * power;
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", std::abs(value) < 1e-12 ? 0.0 : value);
  return text;
}

}  // namespace

Image plot_forces(const std::vector<ForceSeries>& series, int width, int height) {
  Canvas canvas(width, height);
  const int scale = std::max(1, height / 250);
  const int left = 16 * kGlyphAdvance * scale / 2 + 20;
  const int right = width - 20;
  const int top = 40 * scale / 2 + 20;
  const int bottom = height - (kGlyphHeight * scale * 4 + 10);

  double t_end = 0.0;
  double f_max = 0.0;
  for (const ForceSeries& s : series) {
    for (double t : s.time) t_end = std::max(t_end, t);
    for (double f : s.magnitude) {
      if (std::isfinite(f)) f_max = std::max(f_max, f);
    }
  }
  if (t_end <= 0.0) t_end = 1.0;
  if (f_max <= 0.0) f_max = 1.0;
  const double t_step = tick_step(t_end, 8);
  const double f_step = tick_step(f_max, 5);
  const double t_high = std::ceil(t_end / t_step - 1e-9) * t_step;
  const double f_high = std::ceil(f_max / f_step - 1e-9) * f_step;
  const auto x_of = [&](double t) { return left + (right - left) * t / t_high; };
  const auto y_of = [&](double f) { return bottom - (bottom - top) * f / f_high; };

  // grid, ticks and their numbers
  for (double t = 0.0; t <= t_high + 1e-9 * t_high; t += t_step) {
    const int x = static_cast<int>(std::lround(x_of(t)));
    canvas.rect(x, top, 1, bottom - top, kGrid);
    canvas.rect(x, bottom, 1, 5 * scale, kInk);
    const std::string label = number(t);
    canvas.text(label, x - Canvas::text_width(label, scale) / 2, bottom + 8 * scale, scale, kInk);
  }
  for (double f = 0.0; f <= f_high + 1e-9 * f_high; f += f_step) {
    const int y = static_cast<int>(std::lround(y_of(f)));
    canvas.rect(left, y, right - left, 1, kGrid);
    canvas.rect(left - 5 * scale, y, 5 * scale, 1, kInk);
    const std::string label = number(f);
    canvas.text(label, left - 8 * scale - Canvas::text_width(label, scale), y - kGlyphHeight * scale / 2, scale, kInk);
  }
  canvas.rect(left, top, 1, bottom - top + 1, kInk);
  canvas.rect(left, bottom, right - left + 1, 1, kInk);
  const std::string x_label = "TIME [S]";
  canvas.text(x_label, (left + right - Canvas::text_width(x_label, scale)) / 2, bottom + (kGlyphHeight + 16) * scale,
              scale, kInk);
  canvas.text("TOOL FORCE [N]", left - 8 * scale, top - (kGlyphHeight + 12) * scale, scale, kInk);

  // one line per tool, and its name in the key at the top right
  for (std::size_t i = 0; i < series.size(); ++i) {
    const ForceSeries& s = series[i];
    const Rgb& colour = kLines[i % kLines.size()];
    for (std::size_t k = 1; k < s.time.size() && k < s.magnitude.size(); ++k) {
      if (!std::isfinite(s.magnitude[k - 1]) || !std::isfinite(s.magnitude[k])) continue;
      canvas.line(x_of(s.time[k - 1]), y_of(s.magnitude[k - 1]), x_of(s.time[k]), y_of(s.magnitude[k]), colour, 2);
    }
    const int key_y = top - (kGlyphHeight + 12) * scale + static_cast<int>(i) * (kGlyphHeight + 4) * scale;
    const int key_x = right - Canvas::text_width(s.name, scale) - 24 * scale / 2 - 20;
    canvas.rect(key_x, key_y + kGlyphHeight * scale / 2 - 1, 20, 3, colour);
    canvas.text(s.name, key_x + 26, key_y, scale, kInk);
  }
  return canvas.take();
}

}  // namespace cubespring
