// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The off-screen renderer: frames checked against geometry computed without OpenGL (ray-sphere
// silhouettes, projected segment midpoints), determinism of the PNG bytes, anti-aliasing, colour
// maps, the lattice wireframe, the legend, and errors that name the value at fault.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>
#include <Eigen/Geometry>

#include "cubespring/embedding.h"
#include "cubespring/lattice.h"
#include "cubespring/model.h"
#include "cubespring/render/renderer.h"
#include "cubespring/shapes.h"

// OSMesa (Mesa 22) keeps a few hundred bytes per process that it never frees; they are not ours.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOSMesa.so\n"; }

namespace cubespring {
namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;
constexpr double kPi = 3.14159265358979323846;

const Eigen::Vector3d kSphereCentre(0.02, -0.01, 0.015);
constexpr double kSphereRadius = 0.05;

// off-centre and oblique, so a flipped or transposed image would not match
Camera sphere_camera() {
  Camera camera;
  camera.position = Eigen::Vector3d(0.25, -0.3, 0.12);
  camera.target = Eigen::Vector3d(0.0, 0.0, 0.0);
  camera.vertical_fov_degrees = 30;
  return camera;
}

RenderSettings plain_settings(int supersampling) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.supersampling = supersampling;
  settings.background = Eigen::Vector3f::Zero();
  settings.floor = false;
  return settings;
}

struct Surface {
  Eigen::Matrix3Xd vertices;
  Eigen::Matrix3Xd normals;
  Eigen::Matrix3Xi triangles;
};

Surface sphere_surface(int subdivisions, const Eigen::Vector3d& centre = kSphereCentre) {
  const TriangleMesh mesh = sphere_mesh(kSphereRadius, subdivisions, centre);
  Surface s{mesh.vertices, {}, mesh.triangles};
  vertex_normals(s.vertices, s.triangles, s.normals);
  return s;
}

Image render_sphere(Renderer& renderer, const Eigen::Vector3f& colour) {
  const Surface sphere = sphere_surface(4);
  EXPECT_TRUE(renderer.begin_frame(sphere_camera()).ok());
  const Status drawn = renderer.draw_mesh(sphere.vertices, sphere.normals, sphere.triangles, colour);
  EXPECT_TRUE(drawn.ok()) << drawn.message();
  Result<Image> image = renderer.end_frame();
  EXPECT_TRUE(image.ok()) << image.message();
  return image.ok() ? std::move(image).value() : Image{};
}

Renderer make_renderer(const RenderSettings& settings) {
  Result<Renderer> renderer = Renderer::create(settings);
  EXPECT_TRUE(renderer.ok()) << renderer.message();
  return std::move(renderer).value();
}

// the ray through a pixel centre, from the camera's fields alone (pinhole geometry, no matrices)
Eigen::Vector3d pixel_ray(const Camera& camera, double x, double y, int width, int height) {
  const Eigen::Vector3d forward = (camera.target - camera.position).normalized();
  const Eigen::Vector3d right = forward.cross(camera.up).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  const double half_height = std::tan(0.5 * camera.vertical_fov_degrees * kPi / 180.0);
  const double half_width = half_height * width / height;
  return forward + (2.0 * x / width - 1.0) * half_width * right + (1.0 - 2.0 * y / height) * half_height * up;
}

// which pixel centres see the sphere: analytic ray-sphere intersection
std::vector<bool> sphere_coverage(const Camera& camera, int width, int height) {
  std::vector<bool> covered(static_cast<std::size_t>(width * height));
  const Eigen::Vector3d offset = camera.position - kSphereCentre;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const Eigen::Vector3d d = pixel_ray(camera, x + 0.5, y + 0.5, width, height);
      const double b = offset.dot(d);
      const double c = offset.squaredNorm() - kSphereRadius * kSphereRadius;
      covered[static_cast<std::size_t>(y * width + x)] = b * b - d.squaredNorm() * c > 0.0 && b < 0.0;
    }
  }
  return covered;
}

// pixels whose 5 x 5 neighbourhood holds both covered and uncovered centres: within 2 pixels of
// the silhouette
std::vector<bool> near_border(const std::vector<bool>& covered, int width, int height) {
  std::vector<bool> near(covered.size(), false);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const bool self = covered[static_cast<std::size_t>(y * width + x)];
      for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
          const int nx = x + dx;
          const int ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          if (covered[static_cast<std::size_t>(ny * width + nx)] != self)
            near[static_cast<std::size_t>(y * width + x)] = true;
        }
      }
    }
  }
  return near;
}

int max_channel(const Image& image, int x, int y) {
  const std::uint8_t* p = image.pixel(x, y);
  return std::max({p[0], p[1], p[2]});
}

Eigen::Vector3f colour_at(const Image& image, int x, int y) {
  const std::uint8_t* p = image.pixel(x, y);
  return Eigen::Vector3f(p[0], p[1], p[2]) / 255.0f;
}

std::string temp_path(const std::string& name) {
  // other build trees may run the same tests at the same time
  return ::testing::TempDir() + "cubespring_render_" + std::to_string(::getpid()) + "_" + name;
}

std::vector<char> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Camera, ProjectLandsOnThePixelWhoseRayThroughItsCentreHitsThePoint) {
  const Camera camera = sphere_camera();
  for (const auto& [x, y] : {std::pair{0.5, 0.5}, {80.5, 60.5}, {10.5, 100.5}, {159.5, 7.5}}) {
    const Eigen::Vector3d point = camera.position + 0.37 * pixel_ray(camera, x, y, kWidth, kHeight);
    const Eigen::Vector2d pixel = camera.project(point, kWidth, kHeight);
    EXPECT_NEAR(pixel.x(), x, 1e-9);
    EXPECT_NEAR(pixel.y(), y, 1e-9);
  }
}

TEST(Renderer, SphereCoversItsAnalyticSilhouette) {
  Renderer renderer = make_renderer(plain_settings(2));
  const Image image = render_sphere(renderer, Eigen::Vector3f(0.8f, 0.4f, 0.3f));
  ASSERT_EQ(image.width, kWidth);
  ASSERT_EQ(image.height, kHeight);
  ASSERT_EQ(image.rgb.size(), static_cast<std::size_t>(3 * kWidth * kHeight));

  const std::vector<bool> covered = sphere_coverage(sphere_camera(), kWidth, kHeight);
  const std::vector<bool> border = near_border(covered, kWidth, kHeight);
  int checked = 0, agree = 0, inside = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t i = static_cast<std::size_t>(y * kWidth + x);
      if (border[i]) continue;
      ++checked;
      inside += covered[i] ? 1 : 0;
      const int value = max_channel(image, x, y);
      // the dark side still shows the ambient share of the colour (0.25 x 0.8 x 255 = 51)
      if (covered[i] ? value > 8 : value == 0) ++agree;
    }
  }
  EXPECT_GT(inside, 1500) << "the sphere should fill a good part of the frame";
  EXPECT_GE(agree, 0.99 * checked) << agree << " of " << checked << " pixels away from the silhouette agree";
}

TEST(Renderer, SameSceneGivesIdenticalPngBytes) {
  Renderer first = make_renderer(plain_settings(2));
  const Image a = render_sphere(first, Eigen::Vector3f(0.3f, 0.7f, 0.5f));
  const Image b = render_sphere(first, Eigen::Vector3f(0.3f, 0.7f, 0.5f));
  Renderer second = make_renderer(plain_settings(2));
  const Image c = render_sphere(second, Eigen::Vector3f(0.3f, 0.7f, 0.5f));

  const std::string paths[] = {temp_path("twin_a.png"), temp_path("twin_b.png"), temp_path("twin_c.png")};
  ASSERT_TRUE(write_png(a, paths[0]).ok());
  ASSERT_TRUE(write_png(b, paths[1]).ok());
  ASSERT_TRUE(write_png(c, paths[2]).ok());
  const std::vector<char> bytes = file_bytes(paths[0]);
  EXPECT_GT(bytes.size(), 100u);
  EXPECT_EQ(bytes, file_bytes(paths[1])) << "two frames of one renderer differ";
  EXPECT_EQ(bytes, file_bytes(paths[2])) << "frames of two renderers differ";

  // and the file holds the frame exactly
  Result<Image> read = read_png(paths[0]);
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_EQ(read->width, a.width);
  EXPECT_EQ(read->height, a.height);
  EXPECT_EQ(read->rgb, a.rgb);
  for (const std::string& path : paths) std::remove(path.c_str());
}

// unlit white on black: without supersampling every pixel is 0 or 255
int intermediate_pixels(const Image& image, int* near_silhouette) {
  const std::vector<bool> border = near_border(sphere_coverage(sphere_camera(), kWidth, kHeight), kWidth, kHeight);
  int count = 0;
  *near_silhouette = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const int value = image.pixel(x, y)[0];
      if (value == 0 || value == 255) continue;
      ++count;
      if (border[static_cast<std::size_t>(y * kWidth + x)]) ++*near_silhouette;
    }
  }
  return count;
}

TEST(Renderer, SupersamplingBlendsTheSilhouetteEdge) {
  RenderSettings settings = plain_settings(2);
  settings.lights.clear();
  Renderer smooth = make_renderer(settings);
  settings.supersampling = 1;
  Renderer aliased = make_renderer(settings);

  int near_smooth = 0, near_aliased = 0;
  const int blended = intermediate_pixels(render_sphere(smooth, Eigen::Vector3f::Ones()), &near_smooth);
  const int jagged = intermediate_pixels(render_sphere(aliased, Eigen::Vector3f::Ones()), &near_aliased);
  // the silhouette is about 2 pi 28 = 176 pixels long
  EXPECT_GT(blended, 80);
  EXPECT_EQ(near_smooth, blended) << "blended pixels away from the silhouette";
  EXPECT_EQ(jagged, 0);
}

TEST(Renderer, VertexColoursFollowTheColourMap) {
  RenderSettings settings = plain_settings(2);
  settings.lights.clear();
  Renderer renderer = make_renderer(settings);
  Camera camera;
  camera.position = Eigen::Vector3d(0.0, -0.4, 0.0);  // +x to the right of the image
  camera.target = Eigen::Vector3d::Zero();
  camera.vertical_fov_degrees = 30;
  const Surface sphere = sphere_surface(4, Eigen::Vector3d::Zero());
  const ColourMap map = ColourMap::viridis();
  const Eigen::VectorXd x = sphere.vertices.row(0).transpose();
  const Eigen::Matrix3Xf colours = map.colours(x, -kSphereRadius, kSphereRadius);

  ASSERT_TRUE(renderer.begin_frame(camera).ok());
  const Status drawn = renderer.draw_mesh_coloured(sphere.vertices, sphere.normals, sphere.triangles, colours);
  ASSERT_TRUE(drawn.ok()) << drawn.message();
  Result<Image> image = renderer.end_frame();
  ASSERT_TRUE(image.ok()) << image.message();

  // sample the middle row just inside the left and right edges of the sphere
  const Eigen::Vector2d left = camera.project(Eigen::Vector3d(-0.8 * kSphereRadius, 0, 0), kWidth, kHeight);
  const Eigen::Vector2d right = camera.project(Eigen::Vector3d(0.8 * kSphereRadius, 0, 0), kWidth, kHeight);
  const int row = static_cast<int>(left.y());
  const int left_col = static_cast<int>(left.x());
  const int right_col = static_cast<int>(right.x());
  const Eigen::Vector3f on_left = colour_at(*image, left_col, row);
  const Eigen::Vector3f on_right = colour_at(*image, right_col, row);
  const Eigen::Vector3f low = map.colour(0.0), high = map.colour(1.0);
  EXPECT_LT((on_left - low).norm(), (on_right - low).norm());
  EXPECT_LT((on_right - high).norm(), (on_left - high).norm());

  // and each is the map's own colour for the x of the surface that pixel sees (the near side,
  // where perspective puts a smaller |x| than the sphere's outline), give or take interpolation
  auto seen_t = [&](int col) {
    const Eigen::Vector3d d = pixel_ray(camera, col + 0.5, row + 0.5, kWidth, kHeight);
    const Eigen::Vector3d offset = camera.position;  // the sphere is centred on the origin
    const double b = offset.dot(d), c = offset.squaredNorm() - kSphereRadius * kSphereRadius;
    const double distance = (-b - std::sqrt(b * b - d.squaredNorm() * c)) / d.squaredNorm();
    return ((camera.position + distance * d).x() + kSphereRadius) / (2 * kSphereRadius);
  };
  EXPECT_LT((on_left - map.colour(seen_t(left_col))).norm(), 0.04f);
  EXPECT_LT((on_right - map.colour(seen_t(right_col))).norm(), 0.04f);
}

TEST(ColourMap, EndsMidpointAndClamping) {
  const ColourMap map = ColourMap::viridis();
  EXPECT_TRUE(map.colour(0.0).isApprox(Eigen::Vector3f(0x44, 0x01, 0x54) / 255.0f));
  EXPECT_TRUE(map.colour(1.0).isApprox(Eigen::Vector3f(0xFD, 0xE7, 0x25) / 255.0f));
  EXPECT_TRUE(map.colour(0.5).isApprox(Eigen::Vector3f(0x21, 0x90, 0x8C) / 255.0f));
  EXPECT_EQ(map.colour(-3.0), map.colour(0.0));
  EXPECT_EQ(map.colour(7.0), map.colour(1.0));
  EXPECT_EQ(map.colour(std::nan("")), ColourMap::nan_colour());
  const Eigen::Vector3f white = ColourMap::blue_white_red().colour(0.5);
  EXPECT_TRUE(white.isApprox(Eigen::Vector3f::Constant(0xF7 / 255.0f)));

  const Eigen::Matrix3Xd rest = Eigen::Matrix3Xd::Zero(3, 2);
  Eigen::Matrix3Xd moved = rest;
  moved.col(1) = Eigen::Vector3d(0.003, 0.004, 0.0);
  const Eigen::VectorXd d = displacement_magnitudes(rest, moved);
  EXPECT_DOUBLE_EQ(d[0], 0.0);
  EXPECT_DOUBLE_EQ(d[1], 0.005);
}

TEST(Wireframe, BoxOfTwoCellsEachWayHas54EdgesAndTheyShow) {
  Result<Model> model = build_model(box_lattice(Eigen::Vector3i(2, 2, 2), Eigen::Vector3d::Constant(0.01), Material{}));
  ASSERT_TRUE(model.ok()) << model.message();
  Eigen::Matrix3Xd points;
  Eigen::Matrix2Xi segments;
  lattice_wireframe(*model, model->rest_positions, points, segments);

  // 3 axes x 2 cells along x 3 x 3 node lines across = 54 distinct edges of one cell length each
  EXPECT_EQ(points.cols(), 27);
  ASSERT_EQ(segments.cols(), 54);
  std::set<std::pair<int, int>> distinct;
  for (Eigen::Index s = 0; s < segments.cols(); ++s) {
    distinct.insert(std::minmax(segments(0, s), segments(1, s)));
    EXPECT_NEAR((points.col(segments(0, s)) - points.col(segments(1, s))).norm(), 0.01, 1e-12) << "segment " << s;
  }
  EXPECT_EQ(distinct.size(), 54u);

  // every edge shows at its projected midpoint
  Renderer renderer = make_renderer(plain_settings(2));
  Camera camera;
  camera.position = Eigen::Vector3d(0.055, -0.035, 0.045);
  camera.target = Eigen::Vector3d::Constant(0.01);
  ASSERT_TRUE(renderer.begin_frame(camera).ok());
  const Status drawn = renderer.draw_lines(points, segments, Eigen::Vector3f::Ones(), 1.0f);
  ASSERT_TRUE(drawn.ok()) << drawn.message();
  Result<Image> image = renderer.end_frame();
  ASSERT_TRUE(image.ok()) << image.message();
  int lit = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) lit += max_channel(*image, x, y) > 0 ? 1 : 0;
  }
  EXPECT_GT(lit, 300);
  for (Eigen::Index s = 0; s < segments.cols(); ++s) {
    const Eigen::Vector3d middle = 0.5 * (points.col(segments(0, s)) + points.col(segments(1, s)));
    const Eigen::Vector2d pixel = camera.project(middle, kWidth, kHeight);
    int brightest = 0;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = static_cast<int>(pixel.x()) + dx;
        const int y = static_cast<int>(pixel.y()) + dy;
        if (x >= 0 && y >= 0 && x < kWidth && y < kHeight) brightest = std::max(brightest, max_channel(*image, x, y));
      }
    }
    EXPECT_GT(brightest, 100) << "segment " << s << " does not show at pixel " << pixel.transpose();
  }
}

TEST(Renderer, LegendShowsTheMapHighAboveLowAndText) {
  Renderer renderer = make_renderer(plain_settings(2));
  ASSERT_TRUE(renderer.begin_frame(sphere_camera()).ok());
  const ColourMap map = ColourMap::viridis();
  ASSERT_TRUE(renderer.draw_legend(map, 0.0, 0.004, "displacement [m]").ok());
  Result<Image> image = renderer.end_frame();
  ASSERT_TRUE(image.ok()) << image.message();

  // nearest pixels to the map's ends in the right quarter of the frame
  auto nearest = [&](const Eigen::Vector3f& colour, int* row) {
    float best = 1e9f;
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 3 * kWidth / 4; x < kWidth; ++x) {
        const float distance = (colour_at(*image, x, y) - colour).norm();
        if (distance < best) best = distance, *row = y;
      }
    }
    return best;
  };
  int high_row = -1, low_row = -1;
  EXPECT_LT(nearest(map.colour(1.0), &high_row), 0.05f);
  EXPECT_LT(nearest(map.colour(0.0), &low_row), 0.05f);
  EXPECT_LT(high_row, low_row) << "high values belong at the top";
  int text = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = kWidth / 2; x < kWidth; ++x)
      text += image->pixel(x, y)[1] > 200 && image->pixel(x, y)[2] > 200 ? 1 : 0;
  }
  EXPECT_GT(text, 100) << "the numbers and the label are drawn in near-white";
}

TEST(Renderer, FloorAndLightsRender) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  Renderer renderer = make_renderer(settings);
  const Image image = render_sphere(renderer, Eigen::Vector3f(0.8f, 0.4f, 0.3f));
  // the bottom corners see the floor (grey, below the sphere), the top corners the background
  const Eigen::Vector3f floor_corner = colour_at(image, 2, kHeight - 3);
  const Eigen::Vector3f top_corner = colour_at(image, 2, 2);
  EXPECT_TRUE(top_corner.isApprox(settings.background, 0.02f)) << top_corner.transpose();
  EXPECT_GT((floor_corner - settings.background).norm(), 0.1f) << floor_corner.transpose();
}

TEST(Renderer, BadSettingsNameTheValue) {
  RenderSettings settings;
  settings.width = 0;
  Result<Renderer> zero_width = Renderer::create(settings);
  ASSERT_FALSE(zero_width.ok());
  EXPECT_NE(zero_width.message().find("width is 0"), std::string::npos) << zero_width.message();

  settings = RenderSettings{};
  settings.height = -1;
  Result<Renderer> negative_height = Renderer::create(settings);
  ASSERT_FALSE(negative_height.ok());
  EXPECT_NE(negative_height.message().find("height is -1"), std::string::npos) << negative_height.message();

  settings = RenderSettings{};
  settings.width = 100000;
  Result<Renderer> huge = Renderer::create(settings);
  ASSERT_FALSE(huge.ok());
  EXPECT_NE(huge.message().find("100000"), std::string::npos) << huge.message();

  settings = RenderSettings{};
  settings.supersampling = 0;
  Result<Renderer> no_samples = Renderer::create(settings);
  ASSERT_FALSE(no_samples.ok());
  EXPECT_NE(no_samples.message().find("supersampling is 0"), std::string::npos) << no_samples.message();

  settings = RenderSettings{};
  settings.lights.assign(9, Light{});
  EXPECT_FALSE(Renderer::create(settings).ok());
}

TEST(Renderer, BadCallsAndArraysAreErrors) {
  Renderer renderer = make_renderer(plain_settings(1));
  const Surface sphere = sphere_surface(1);
  const Eigen::Vector3f white = Eigen::Vector3f::Ones();

  const Status early = renderer.draw_mesh(sphere.vertices, sphere.normals, sphere.triangles, white);
  EXPECT_NE(early.message().find("begin_frame"), std::string::npos) << early.message();

  Camera blind;
  blind.position = blind.target;
  const Status no_direction = renderer.begin_frame(blind);
  EXPECT_NE(no_direction.message().find("position"), std::string::npos) << no_direction.message();

  ASSERT_TRUE(renderer.begin_frame(sphere_camera()).ok());
  Eigen::Matrix3Xi bad = sphere.triangles;
  bad(2, 5) = 99;
  const Status out_of_range = renderer.draw_mesh(sphere.vertices, sphere.normals, bad, white);
  EXPECT_NE(out_of_range.message().find("triangle 5 names vertex 99"), std::string::npos) << out_of_range.message();
  const Status few_normals = renderer.draw_mesh(sphere.vertices, sphere.normals.leftCols(3), sphere.triangles, white);
  EXPECT_FALSE(few_normals.ok());
  Eigen::Matrix2Xi segment(2, 1);
  segment << 0, -1;
  EXPECT_NE(renderer.draw_lines(sphere.vertices, segment, white).message().find("point -1"), std::string::npos);
  EXPECT_TRUE(renderer.end_frame().ok());
  EXPECT_FALSE(renderer.end_frame().ok()) << "a frame ends once";

  // a moved-from renderer refuses politely
  Renderer moved = std::move(renderer);
  EXPECT_FALSE(renderer.begin_frame(sphere_camera()).ok());  // NOLINT(bugprone-use-after-move)
  EXPECT_TRUE(moved.begin_frame(sphere_camera()).ok());
  EXPECT_TRUE(moved.end_frame().ok());
}

TEST(Renderer, AFrameInterruptedByAnotherRendererRefusesToDraw) {
  Renderer a = make_renderer(plain_settings(1));
  Renderer b = make_renderer(plain_settings(1));
  const Surface sphere = sphere_surface(2);
  ASSERT_TRUE(a.begin_frame(sphere_camera()).ok());
  ASSERT_TRUE(b.begin_frame(sphere_camera()).ok());
  const Status interrupted = a.draw_mesh(sphere.vertices, sphere.normals, sphere.triangles, Eigen::Vector3f::Ones());
  EXPECT_NE(interrupted.message().find("another Renderer"), std::string::npos) << interrupted.message();
  EXPECT_TRUE(b.end_frame().ok());

  // a fresh frame of the first renderer works again
  const Image image = render_sphere(a, Eigen::Vector3f::Ones());
  EXPECT_EQ(image.width, kWidth);
}

TEST(Png, UnwritableAndMissingPathsAreNamed) {
  Image image;
  image.width = 2;
  image.height = 1;
  image.rgb = {255, 0, 0, 0, 0, 255};
  const std::string unwritable = "/nonexistent/dir/x.png";
  const Status written = write_png(image, unwritable);
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.message().find(unwritable), std::string::npos) << written.message();

  const Result<Image> missing = read_png("/nonexistent/dir/y.png");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("/nonexistent/dir/y.png"), std::string::npos) << missing.message();

  image.rgb.pop_back();
  const std::string path = temp_path("short.png");
  const Status short_pixels = write_png(image, path);
  ASSERT_FALSE(short_pixels.ok());
  EXPECT_NE(short_pixels.message().find(path), std::string::npos) << short_pixels.message();
}

}  // namespace
}  // namespace cubespring
