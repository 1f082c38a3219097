// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "legend.h"

#include <algorithm>
#include <cstdio>

#include <GL/gl.h>

#include "bitmap_font.h"

namespace cubespring {
namespace {

constexpr int kBarSteps = 64;  // colour bands of the bar; smooth shading blends between them

// layout in output pixels from the top-left corner; the projection maps these units onto the
// supersampled frame, so a rectangle on whole units covers whole output pixels
void fill_rect(int x, int y, int width, int height, const Eigen::Vector3f& colour) {
  glColor3f(colour.x(), colour.y(), colour.z());
  glBegin(GL_QUADS);
  glVertex2i(x, y);
  glVertex2i(x, y + height);
  glVertex2i(x + width, y + height);
  glVertex2i(x + width, y);
  glEnd();
}

int text_width(const std::string& text, int scale) {
  return text.empty() ? 0 : (static_cast<int>(text.size()) * kGlyphAdvance - 1) * scale;
}

void draw_text(const std::string& text, int x, int y, int scale, const Eigen::Vector3f& colour) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const int left = x + static_cast<int>(i) * kGlyphAdvance * scale;
    for (int row = 0; row < kGlyphHeight; ++row) {
      for (int column = 0; column < kGlyphWidth; ++column) {
        if (glyph_pixel(text[i], column, row)) fill_rect(left + column * scale, y + row * scale, scale, scale, colour);
      }
    }
  }
}

// text with a one-font-pixel drop shadow, readable over the background and the floor alike
void draw_shadowed_text(const std::string& text, int x, int y, int scale, const Eigen::Vector3f& ink,
                        const Eigen::Vector3f& shadow) {
  draw_text(text, x + scale, y + scale, scale, shadow);
  draw_text(text, x, y, scale, ink);
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

}  // namespace

void draw_legend_overlay(const LegendRequest& legend, int output_width, int output_height,
                         const Eigen::Vector3f& background) {
  // 2D in output pixels, y down
  glDisable(GL_LIGHTING);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glShadeModel(GL_SMOOTH);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0.0, output_width, output_height, 0.0, -1.0, 1.0);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();

  // ink that stands out from the background: white on dark, black on light
  const float luminance = 0.2126f * background.x() + 0.7152f * background.y() + 0.0722f * background.z();
  const Eigen::Vector3f ink =
      luminance < 0.5f ? Eigen::Vector3f(0.95f, 0.95f, 0.95f) : Eigen::Vector3f(0.05f, 0.05f, 0.05f);
  const Eigen::Vector3f shadow = Eigen::Vector3f::Ones() - ink;

  // bar at the right edge, centred vertically; the font grows with the image (1 unit up to 719 rows)
  const int scale = std::max(1, output_height / 360);
  const int margin = 10 * scale;
  const int bar_width = 12 * scale;
  const int bar_height = std::max(20, output_height * 45 / 100);
  const int bar_x = output_width - margin - bar_width;
  const int bar_y = (output_height - bar_height) / 2;

  // frame, then the bands from low (bottom) to high (top)
  fill_rect(bar_x - scale, bar_y - scale, bar_width + 2 * scale, bar_height + 2 * scale, ink);
  glBegin(GL_QUAD_STRIP);
  for (int step = 0; step <= kBarSteps; ++step) {
    const double t = static_cast<double>(step) / kBarSteps;
    const Eigen::Vector3f colour = legend.map.colour(t);
    const double y = bar_y + (1.0 - t) * bar_height;
    glColor3f(colour.x(), colour.y(), colour.z());
    glVertex2d(bar_x, y);
    glVertex2d(bar_x + bar_width, y);
  }
  glEnd();

  // ticks and values at high, middle and low, right-aligned left of the bar
  for (double t : {1.0, 0.5, 0.0}) {
    const int y = bar_y + static_cast<int>((1.0 - t) * bar_height + 0.5);
    fill_rect(bar_x - 4 * scale, y - scale / 2, 3 * scale, scale, ink);
    const std::string text = number(legend.low + t * (legend.high - legend.low));
    const int text_x = bar_x - 6 * scale - text_width(text, scale);
    draw_shadowed_text(text, text_x, y - kGlyphHeight * scale / 2, scale, ink, shadow);
  }

  // label above the bar, flush with its right edge
  const int label_y = bar_y - (kGlyphHeight + 9) * scale;
  draw_shadowed_text(legend.label, bar_x + bar_width - text_width(legend.label, scale), label_y, scale, ink, shadow);
}

}  // namespace cubespring
