// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Frames through OSMesa's fixed-function OpenGL: the scene is rendered at supersampling x the
// output size into a buffer we own, then each block of pixels is averaged into one.
#include "cubespring/render/renderer.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <new>
#include <optional>
#include <utility>

#include <GL/gl.h>
#include <GL/osmesa.h>

#include "legend.h"

namespace cubespring {
namespace {

constexpr int kMaxRenderSide = 8192;  // rendered pixels a side: our buffer, OSMesa's colour and depth
                                      // surfaces take 4 bytes a pixel each, 768 MiB at most
constexpr int kMaxSupersampling = 8;
constexpr int kMaxLights = 8;  // GL_LIGHT0 .. GL_LIGHT7 of the fixed pipeline
constexpr int kMaxFloorTilesPerSide = 400;
constexpr float kSpecular = 0.15f;  // a faint highlight shows the shape of smooth surfaces
constexpr float kShininess = 32.0f;
constexpr float kCheckerDarkening = 0.85f;

bool in_unit_range(const Eigen::Vector3f& colour) {
  return colour.allFinite() && (colour.array() >= 0.0f).all() && (colour.array() <= 1.0f).all();
}

std::string text(const Eigen::Vector3f& v) {
  return "(" + std::to_string(v.x()) + ", " + std::to_string(v.y()) + ", " + std::to_string(v.z()) + ")";
}

Status check_side(const char* name, int value, int supersampling) {
  if (value < 1) {
    return Status::error(std::string("RenderSettings::") + name + " is " + std::to_string(value) +
                         " pixels: it must be at least 1");
  }
  const int most = kMaxRenderSide / supersampling;
  if (value > most) {
    return Status::error(std::string("RenderSettings::") + name + " is " + std::to_string(value) +
                         " pixels: with supersampling " + std::to_string(supersampling) + " it must be at most " +
                         std::to_string(most) + " (" + std::to_string(kMaxRenderSide) + " rendered pixels a side)");
  }
  return {};
}

Status check_settings(const RenderSettings& s) {
  if (s.width < 1) return check_side("width", s.width, 1);
  if (s.height < 1) return check_side("height", s.height, 1);
  if (s.supersampling < 1 || s.supersampling > kMaxSupersampling) {
    return Status::error("RenderSettings::supersampling is " + std::to_string(s.supersampling) + ": it must be 1 to " +
                         std::to_string(kMaxSupersampling));
  }
  if (Status side = check_side("width", s.width, s.supersampling); !side) return side;
  if (Status side = check_side("height", s.height, s.supersampling); !side) return side;
  if (!in_unit_range(s.background)) {
    return Status::error("RenderSettings::background is " + text(s.background) + ": each channel must be in [0, 1]");
  }
  if (s.lights.size() > static_cast<std::size_t>(kMaxLights)) {
    return Status::error("RenderSettings::lights has " + std::to_string(s.lights.size()) +
                         " lights: OpenGL's fixed pipeline takes at most " + std::to_string(kMaxLights));
  }
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const Light& light = s.lights[i];
    if (!light.direction.allFinite() || !(light.direction.norm() > 0.0)) {
      return Status::error("RenderSettings::lights[" + std::to_string(i) + "].direction is zero or not finite");
    }
    if (!light.colour.allFinite() || (light.colour.array() < 0.0f).any()) {
      return Status::error("RenderSettings::lights[" + std::to_string(i) + "].colour is " + text(light.colour) +
                           ": each channel must be finite and >= 0");
    }
  }
  if (!(s.ambient >= 0.0f && s.ambient <= 1.0f)) {
    return Status::error("RenderSettings::ambient is " + std::to_string(s.ambient) + ": it must be in [0, 1]");
  }
  if (!std::isfinite(s.floor_height)) return Status::error("RenderSettings::floor_height is not finite");
  if (!(s.floor_half_size > 0.0 && std::isfinite(s.floor_half_size))) {
    return Status::error("RenderSettings::floor_half_size is " + std::to_string(s.floor_half_size) +
                         " m: it must be finite and > 0");
  }
  if (!(s.floor_tile_size >= 0.0 && std::isfinite(s.floor_tile_size))) {
    return Status::error("RenderSettings::floor_tile_size is " + std::to_string(s.floor_tile_size) +
                         " m: it must be >= 0 (0 for a plain floor)");
  }
  if (s.floor_tile_size > 0.0 && 2.0 * s.floor_half_size / s.floor_tile_size > kMaxFloorTilesPerSide) {
    return Status::error("RenderSettings::floor_tile_size is " + std::to_string(s.floor_tile_size) +
                         " m: the floor would have more than " + std::to_string(kMaxFloorTilesPerSide) +
                         " tiles a side; use larger tiles, a smaller floor_half_size or 0 for a plain floor");
  }
  if (!in_unit_range(s.floor_colour)) {
    return Status::error("RenderSettings::floor_colour is " + text(s.floor_colour) +
                         ": each channel must be in [0, 1]");
  }
  return {};
}

void set_lights(const RenderSettings& settings) {
  // call with the view matrix loaded: directions are then taken in the world frame
  for (int i = 0; i < kMaxLights; ++i) {
    const GLenum light = static_cast<GLenum>(GL_LIGHT0 + i);
    if (i >= static_cast<int>(settings.lights.size())) {
      glDisable(light);
      continue;
    }
    const Light& l = settings.lights[static_cast<std::size_t>(i)];
    const Eigen::Vector3f towards = -l.direction.normalized().cast<float>();
    const GLfloat position[4] = {towards.x(), towards.y(), towards.z(), 0.0f};  // w = 0: directional
    const GLfloat colour[4] = {l.colour.x(), l.colour.y(), l.colour.z(), 1.0f};
    const GLfloat black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    glLightfv(light, GL_POSITION, position);
    glLightfv(light, GL_DIFFUSE, colour);
    glLightfv(light, GL_SPECULAR, colour);
    glLightfv(light, GL_AMBIENT, black);
    glEnable(light);
  }
  const GLfloat ambient[4] = {settings.ambient, settings.ambient, settings.ambient, 1.0f};
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
  // open meshes and the floor's underside show their back faces: light those too
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
  glEnable(GL_COLOR_MATERIAL);
  glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
  const GLfloat specular[4] = {kSpecular, kSpecular, kSpecular, 1.0f};
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, specular);
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, kShininess);
}

void set_lighting(const RenderSettings& settings, bool lit) {
  if (lit && !settings.lights.empty()) {
    glEnable(GL_LIGHTING);
  } else {
    glDisable(GL_LIGHTING);
  }
}

void draw_floor(const RenderSettings& settings, const Eigen::Vector3d& centre) {
  set_lighting(settings, true);
  glNormal3f(0.0f, 0.0f, 1.0f);
  const double z = settings.floor_height;
  const Eigen::Vector3f light = settings.floor_colour;
  const Eigen::Vector3f dark = kCheckerDarkening * settings.floor_colour;
  const double tile = settings.floor_tile_size;
  const double half = settings.floor_half_size;
  glBegin(GL_QUADS);
  if (tile <= 0.0) {
    glColor3f(light.x(), light.y(), light.z());
    glVertex3d(centre.x() - half, centre.y() - half, z);
    glVertex3d(centre.x() + half, centre.y() - half, z);
    glVertex3d(centre.x() + half, centre.y() + half, z);
    glVertex3d(centre.x() - half, centre.y() + half, z);
  } else {
    // tiles on the world grid, so the checker stays put when the camera moves
    const long first_i = static_cast<long>(std::floor((centre.x() - half) / tile));
    const long last_i = static_cast<long>(std::ceil((centre.x() + half) / tile));
    const long first_j = static_cast<long>(std::floor((centre.y() - half) / tile));
    const long last_j = static_cast<long>(std::ceil((centre.y() + half) / tile));
    for (long i = first_i; i < last_i; ++i) {
      for (long j = first_j; j < last_j; ++j) {
        const Eigen::Vector3f& c = ((i + j) % 2 == 0) ? light : dark;
        const double x0 = static_cast<double>(i) * tile;
        const double y0 = static_cast<double>(j) * tile;
        glColor3f(c.x(), c.y(), c.z());
        glVertex3d(x0, y0, z);
        glVertex3d(x0 + tile, y0, z);
        glVertex3d(x0 + tile, y0 + tile, z);
        glVertex3d(x0, y0 + tile, z);
      }
    }
  }
  glEnd();
}

Status check_indices(const char* call, const char* what, const int* indices, Eigen::Index per_item, Eigen::Index items,
                     Eigen::Index num_points, const char* point_name) {
  if (items * per_item > std::numeric_limits<GLsizei>::max()) {
    return Status::error(std::string(call) + ": " + std::to_string(items) + " " + what +
                         "s are more than OpenGL can draw in one call");
  }
  for (Eigen::Index k = 0; k < items * per_item; ++k) {
    if (indices[k] < 0 || indices[k] >= num_points) {
      return Status::error(std::string(call) + ": " + what + " " + std::to_string(k / per_item) + " names " +
                           point_name + " " + std::to_string(indices[k]) + "; there are " + std::to_string(num_points) +
                           " " + point_name + "s");
    }
  }
  return {};
}

Status check_mesh(const char* call, const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xd& normals,
                  const Eigen::Matrix3Xi& triangles) {
  if (normals.cols() != vertices.cols()) {
    return Status::error(std::string(call) + ": normals has " + std::to_string(normals.cols()) +
                         " columns and vertices " + std::to_string(vertices.cols()) + ": one normal per vertex");
  }
  return check_indices(call, "triangle", triangles.data(), 3, triangles.cols(), vertices.cols(), "vertex");
}

}  // namespace

struct Renderer::Context {
  RenderSettings settings;
  int render_width = 0;  // output size x supersampling [pixels]
  int render_height = 0;
  std::vector<std::uint8_t> buffer;  // RGBA, bottom row first (OSMesa's default), render size
  OSMesaContext osmesa = nullptr;
  bool in_frame = false;
  std::optional<LegendRequest> legend;

  Context() = default;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  ~Context() {
    if (osmesa == nullptr) return;
    // release it first so the thread is not left with a current context that no longer exists
    if (OSMesaGetCurrentContext() == osmesa) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(osmesa);
  }

  bool make_current() {
    return OSMesaMakeCurrent(osmesa, buffer.data(), GL_UNSIGNED_BYTE, render_width, render_height) == GL_TRUE;
  }
};

Result<Renderer> Renderer::create(const RenderSettings& settings) {
  if (Status valid = check_settings(settings); !valid) return valid;

  auto context = std::make_unique<Context>();
  context->settings = settings;
  context->render_width = settings.width * settings.supersampling;
  context->render_height = settings.height * settings.supersampling;
  const std::size_t bytes =
      4 * static_cast<std::size_t>(context->render_width) * static_cast<std::size_t>(context->render_height);
  try {
    context->buffer.assign(bytes, 0);
  } catch (const std::bad_alloc&) {
    return Status::error("Renderer: cannot allocate " + std::to_string(bytes) + " bytes for a " +
                         std::to_string(context->render_width) + " x " + std::to_string(context->render_height) +
                         " frame");
  }

  // RGBA with a 24-bit depth buffer; no stencil or accumulation buffer is needed
  context->osmesa = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (context->osmesa == nullptr) {
    return Status::error(
        "Renderer: OSMesaCreateContextExt failed to create an RGBA context with a 24-bit depth "
        "buffer (is libOSMesa's driver installed?)");
  }
  if (!context->make_current()) {
    return Status::error("Renderer: OSMesaMakeCurrent failed for a " + std::to_string(context->render_width) + " x " +
                         std::to_string(context->render_height) + " frame");
  }
  return Renderer(std::move(context));
}

Renderer::Renderer(std::unique_ptr<Context> context) : context_(std::move(context)) {}
Renderer::Renderer(Renderer&& other) noexcept = default;
Renderer& Renderer::operator=(Renderer&& other) noexcept = default;
Renderer::~Renderer() = default;

const RenderSettings& Renderer::settings() const {
  static const RenderSettings kNone{};
  return context_ ? context_->settings : kNone;
}

Status Renderer::begin_frame(const Camera& camera) {
  if (!context_) return Status::error("Renderer::begin_frame: this Renderer was moved from");
  if (Status valid = validate(camera); !valid) return Status::error("Renderer::begin_frame: " + valid.message());
  Context& c = *context_;
  if (!c.make_current()) return Status::error("Renderer::begin_frame: OSMesaMakeCurrent failed");
  const RenderSettings& s = c.settings;

  // fixed state; dithering would add a pattern the block average then smears
  glViewport(0, 0, c.render_width, c.render_height);
  glDisable(GL_DITHER);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glShadeModel(GL_SMOOTH);
  glEnable(GL_NORMALIZE);
  // surfaces sit slightly behind lines drawn on them (wireframes over meshes)
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  glClearColor(s.background.x(), s.background.y(), s.background.z(), 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  // the camera's own matrices, so that Camera::project agrees with the pixels
  const double aspect = static_cast<double>(s.width) / static_cast<double>(s.height);
  const Eigen::Matrix4d projection = camera.projection(aspect);
  const Eigen::Matrix4d view = camera.view();
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(projection.data());
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(view.data());
  set_lights(s);

  if (s.floor) draw_floor(s, camera.target);
  c.in_frame = true;
  c.legend.reset();
  return {};
}

Status Renderer::check_drawing(const char* call) const {
  if (!context_) return Status::error(std::string(call) + ": this Renderer was moved from");
  if (!context_->in_frame) return Status::error(std::string(call) + ": no frame is open: call begin_frame first");
  if (OSMesaGetCurrentContext() != context_->osmesa) {
    return Status::error(std::string(call) +
                         ": another Renderer began a frame on this thread since begin_frame; finish one frame "
                         "(end_frame) before beginning the next");
  }
  return {};
}

Status Renderer::draw_mesh(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xd& normals,
                           const Eigen::Matrix3Xi& triangles, const Eigen::Vector3f& colour) {
  const char* call = "Renderer::draw_mesh";
  if (Status ready = check_drawing(call); !ready) return ready;
  if (Status valid = check_mesh(call, vertices, normals, triangles); !valid) return valid;
  if (triangles.cols() == 0) return {};

  set_lighting(context_->settings, true);
  glColor3f(colour.x(), colour.y(), colour.z());
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glVertexPointer(3, GL_DOUBLE, 0, vertices.data());
  glNormalPointer(GL_DOUBLE, 0, normals.data());
  // indices are checked to be >= 0 above, so reading them as unsigned changes nothing
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * triangles.cols()), GL_UNSIGNED_INT, triangles.data());
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  return {};
}

Status Renderer::draw_mesh_coloured(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xd& normals,
                                    const Eigen::Matrix3Xi& triangles, const Eigen::Matrix3Xf& vertex_colours) {
  const char* call = "Renderer::draw_mesh_coloured";
  if (Status ready = check_drawing(call); !ready) return ready;
  if (Status valid = check_mesh(call, vertices, normals, triangles); !valid) return valid;
  if (vertex_colours.cols() != vertices.cols()) {
    return Status::error(std::string(call) + ": vertex_colours has " + std::to_string(vertex_colours.cols()) +
                         " columns and vertices " + std::to_string(vertices.cols()) + ": one colour per vertex");
  }
  if (triangles.cols() == 0) return {};

  set_lighting(context_->settings, true);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_DOUBLE, 0, vertices.data());
  glNormalPointer(GL_DOUBLE, 0, normals.data());
  glColorPointer(3, GL_FLOAT, 0, vertex_colours.data());
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * triangles.cols()), GL_UNSIGNED_INT, triangles.data());
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  return {};
}

Status Renderer::draw_lines(const Eigen::Matrix3Xd& points, const Eigen::Matrix2Xi& segments,
                            const Eigen::Vector3f& colour, float width_pixels, LineVisibility visibility) {
  const char* call = "Renderer::draw_lines";
  if (Status ready = check_drawing(call); !ready) return ready;
  constexpr float kMaxLineWidth = 32.0f;  // rendered widths stay within OpenGL's range (255) up to 8x supersampling
  if (!(width_pixels > 0.0f && width_pixels <= kMaxLineWidth)) {
    return Status::error(std::string(call) + ": width_pixels is " + std::to_string(width_pixels) +
                         ": it must be in (0, " + std::to_string(kMaxLineWidth) + "]");
  }
  if (Status valid = check_indices(call, "segment", segments.data(), 2, segments.cols(), points.cols(), "point");
      !valid) {
    return valid;
  }
  if (segments.cols() == 0) return {};

  set_lighting(context_->settings, false);
  glLineWidth(width_pixels * static_cast<float>(context_->settings.supersampling));
  glColor3f(colour.x(), colour.y(), colour.z());
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_DOUBLE, 0, points.data());
  // without the depth test the lines neither hide nor write depth, so later surfaces cover them
  if (visibility == LineVisibility::kOverlay) glDisable(GL_DEPTH_TEST);
  glDrawElements(GL_LINES, static_cast<GLsizei>(2 * segments.cols()), GL_UNSIGNED_INT, segments.data());
  glEnable(GL_DEPTH_TEST);
  glDisableClientState(GL_VERTEX_ARRAY);
  return {};
}

Status Renderer::draw_legend(const ColourMap& map, double low, double high, const std::string& label) {
  const char* call = "Renderer::draw_legend";
  if (Status ready = check_drawing(call); !ready) return ready;
  if (!std::isfinite(low) || !std::isfinite(high)) {
    return Status::error(std::string(call) + ": the range [" + std::to_string(low) + ", " + std::to_string(high) +
                         "] is not finite");
  }
  context_->legend = LegendRequest{map, low, high, label};
  return {};
}

Result<Image> Renderer::end_frame() {
  if (Status ready = check_drawing("Renderer::end_frame"); !ready) return ready;
  Context& c = *context_;
  const RenderSettings& s = c.settings;
  c.in_frame = false;

  if (c.legend) draw_legend_overlay(*c.legend, s.width, s.height, s.background);
  // OSMesa renders into its own surface and copies it into our buffer when the work finishes
  glFinish();
  if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
    return Status::error("Renderer::end_frame: OpenGL reported error " + std::to_string(error));
  }

  // average each supersampling x supersampling block, flipping rows to top-first
  const int n = s.supersampling;
  const unsigned block = static_cast<unsigned>(n * n);
  Image image;
  image.width = s.width;
  image.height = s.height;
  image.rgb.resize(3 * static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height));
  std::uint8_t* out = image.rgb.data();
  for (int row = 0; row < s.height; ++row) {
    for (int col = 0; col < s.width; ++col) {
      unsigned sum[3] = {0, 0, 0};
      for (int k = 0; k < n; ++k) {
        const std::size_t render_row = static_cast<std::size_t>(c.render_height - 1 - (row * n + k));
        const std::uint8_t* in =
            &c.buffer[4 * (render_row * static_cast<std::size_t>(c.render_width) + static_cast<std::size_t>(col * n))];
        for (int l = 0; l < n; ++l, in += 4) {
          sum[0] += in[0];
          sum[1] += in[1];
          sum[2] += in[2];
        }
      }
      for (unsigned channel : sum) *out++ = static_cast<std::uint8_t>((channel + block / 2) / block);
    }
  }
  return image;
}

}  // namespace cubespring
