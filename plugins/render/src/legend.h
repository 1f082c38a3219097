// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The colour bar drawn over a finished frame.
#pragma once

#include <string>

#include <Eigen/Core>

#include "cubespring/render/colour_map.h"

namespace cubespring {

/// What Renderer::draw_legend asked for, kept until the frame ends so that the bar lies over the
/// whole scene whatever the order of the draw calls.
struct LegendRequest {
  ColourMap map;
  double low = 0.0;
  double high = 1.0;
  std::string label;
};

/// Draws the legend with OpenGL into the current context, whose frame is output_width x
/// output_height output pixels (each supersampled; the viewport covers the frame). Leaves
/// lighting and the depth test off and the matrices set for 2D.
void draw_legend_overlay(const LegendRequest& legend, int output_width, int output_height,
                         const Eigen::Vector3f& background);

}  // namespace cubespring
