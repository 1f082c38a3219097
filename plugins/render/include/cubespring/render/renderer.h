// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cubespring/render/camera.h"
#include "cubespring/render/colour_map.h"
#include "cubespring/render/image.h"
#include "cubespring/render/lights.h"
#include "cubespring/render/wireframe.h"
#include "cubespring/result.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals. World z is up
/// (the floor is a plane of constant z); image sizes and line widths are in pixels of the output.
namespace cubespring {

/// Whether lines hide behind the surfaces of the frame.
enum class LineVisibility {
  kDepthTested,  ///< hidden where a surface is in front of them, like any object
  kOverlay,      ///< drawn over everything already in the frame, as a see-through wire model
};

/// Everything about frames that does not change from one frame to the next.
struct RenderSettings {
  int width = 1280;  ///< output image width [pixels], >= 1
  int height = 720;  ///< output image height [pixels], >= 1
  /// Anti-aliasing: render at supersampling x the size and average each block down, 1 to 8.
  /// The rendered size (width x supersampling, height x supersampling) is at most 8192 a side.
  int supersampling = 2;
  Eigen::Vector3f background{0.16f, 0.18f, 0.21f};  ///< RGB in [0, 1]
  /// Up to 8 lights (OpenGL's fixed pipeline). None means unlit: every surface shows its colour as
  /// is (flat masks for tests and overlays).
  std::vector<Light> lights = default_lights();
  float ambient = 0.25f;          ///< fraction of a surface's colour seen without any light, in [0, 1]
  bool floor = true;              ///< draw a checkered floor under the scene
  double floor_height = 0.0;      ///< z of the floor plane [m]
  double floor_half_size = 0.5;   ///< the floor spans +-this in x and y around the camera target [m], > 0
  double floor_tile_size = 0.02;  ///< checker tile edge [m]; 0 for a plain floor
  Eigen::Vector3f floor_colour{0.62f, 0.62f, 0.58f};  ///< RGB in [0, 1]; every other tile is 15% darker
};

/// Off-screen frames through OSMesa (Mesa's software OpenGL; no display or GPU needed).
///
/// Usage: create() once; then per frame begin_frame(), any draw_* calls, end_frame(). Draw calls
/// check their arrays and return an error (drawing nothing) on a shape mismatch or an index out of
/// range; positions are not checked for NaN (a blown-up body still renders what it can).
///
/// Each Renderer owns an OpenGL context, which begin_frame() makes current on the calling thread.
/// Only one frame may be open at a time per thread: OSMesa keeps one current context, so a
/// Renderer whose context was replaced mid-frame by another Renderer's begin_frame() refuses to
/// draw rather than draw into the other frame. Renderers are not for concurrent use from several
/// threads. Frames are deterministic: the same calls give the same pixels, whatever the number of
/// rasterizer threads (LP_NUM_THREADS), for one Mesa build and driver (llvmpipe, the default, and
/// softpipe, chosen by GALLIUM_DRIVER, give different pixels).
class Renderer {
 public:
  /// Checks the settings (each fault names the field and its value) and creates the context.
  static Result<Renderer> create(const RenderSettings& settings);

  Renderer(Renderer&& other) noexcept;
  Renderer& operator=(Renderer&& other) noexcept;
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;
  ~Renderer();  ///< destroys the OpenGL context

  const RenderSettings& settings() const;

  /// Starts a frame: clears to the background, sets the camera and lights, draws the floor.
  Status begin_frame(const Camera& camera);

  /// A lit surface of one colour. vertices and normals (3 x n) [m] and [-] (unit length preferred;
  /// see vertex_normals()), triangles (3 x m) vertex indices, colour RGB in [0, 1].
  Status draw_mesh(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xd& normals, const Eigen::Matrix3Xi& triangles,
                   const Eigen::Vector3f& colour);
  /// A lit surface coloured per vertex (3 x n) RGB in [0, 1], interpolated across triangles, e.g.
  /// ColourMap::colours() of a displacement field.
  Status draw_mesh_coloured(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xd& normals,
                            const Eigen::Matrix3Xi& triangles, const Eigen::Matrix3Xf& vertex_colours);
  /// Unlit line segments between points (3 x n) [m]; segments (2 x m) are point indices. Lines win
  /// over surfaces they lie on (surfaces are pushed back slightly in depth). As an overlay they
  /// show through the surfaces drawn before them, and surfaces drawn after them cover them.
  Status draw_lines(const Eigen::Matrix3Xd& points, const Eigen::Matrix2Xi& segments, const Eigen::Vector3f& colour,
                    float width_pixels = 1.0f, LineVisibility visibility = LineVisibility::kDepthTested);
  /// A colour bar at the right edge with `high` at the top, `low` at the bottom and their midpoint,
  /// written in a built-in 5x7 pixel font (letters shown upper case), and `label` above it. Drawn
  /// over the scene when the frame ends; a second call in one frame replaces the first.
  Status draw_legend(const ColourMap& map, double low, double high, const std::string& label = "");

  /// Finishes the frame and returns it, supersampled down to the output size.
  Result<Image> end_frame();

 private:
  struct Context;
  explicit Renderer(std::unique_ptr<Context> context);
  Status check_drawing(const char* call) const;

  std::unique_ptr<Context> context_;
};

}  // namespace cubespring
