// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A line plot of each tool's contact force magnitude over time, drawn straight into an Image with
// the renderer's built-in font (no OpenGL): what `cubespring run` writes as tool_force.png.
#pragma once

#include <string>
#include <vector>

#include "cubespring/render/image.h"

namespace cubespring {

struct ForceSeries {
  std::string name;               ///< the tool's name, shown in the key
  std::vector<double> time;       ///< [s]
  std::vector<double> magnitude;  ///< |force| at each time [N]
};

/// Axes with numbered ticks (time in seconds across, force in newtons up), one coloured line per
/// series and a key with their names; width x height pixels.
Image plot_forces(const std::vector<ForceSeries>& series, int width = 1000, int height = 500);

}  // namespace cubespring
