// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// make_demo_meshes: writes the surface meshes of the surgical demo in metres, a liver with a
// stiffer tumour inside it (liver.obj + liver.mtl) and a round-tipped probe (probe.obj +
// probe.mtl), after checking that every part is a closed, outward-oriented triangle surface.
//
// Usage: make_demo_meshes OUTPUT_DIR
//
// The output is the same bytes on every run: there is no randomness, and coordinates are rounded
// to the written precision before they are checked, so the checks apply to what is written.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace {

using Vec3 = Eigen::Vector3d;
using Triangle = std::array<int, 3>;

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Sizes [m]

// The liver before shaping is an ellipsoid of these half extents; the shaping below only shrinks
// or swells it, so the final size is measured (and printed), not set.
const Vec3 kLiverReferenceHalfExtents{0.11, 0.08, 0.04};
constexpr int kLiverSubdivisions = 4;  // 20 * 4^4 = 5120 triangles

const Vec3 kTumourHalfExtents{0.016, 0.014, 0.012};  // about 3 cm across, about 11 ml
constexpr int kTumourSubdivisions = 3;               // 1280 triangles
constexpr double kProbePointX = 0.03;                // where the probe presses, at y = 0
constexpr double kTumourHeightFraction = 0.55;       // of the liver's thickness there, from below
constexpr double kMinTumourClearance = 0.01;

constexpr double kProbeRadius = 0.0025;  // a 5 mm shaft
constexpr double kProbeLength = 0.20;    // from the tip to the flat top cap
constexpr int kProbeSegments = 32;       // vertices around
constexpr int kProbeTipRings = 8;        // rings on the hemisphere, pole excluded
constexpr int kProbeShaftRings = 20;     // one every ~1 cm, so shaft triangles are not needles

constexpr double kWrittenResolution = 1e-7;  // coordinates are written with 7 decimals
constexpr double kMinTriangleArea = 1e-12;   // [m^2]; the smallest real one is ~2e-8

// ---------------------------------------------------------------------------------------------
// Triangle meshes

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;  // counter-clockwise seen from outside

  int num_vertices() const { return static_cast<int>(vertices.size()); }
  int num_triangles() const { return static_cast<int>(triangles.size()); }
};

struct Part {
  std::string name;
  std::string material;
  Mesh mesh;
};

Vec3 corner(const Mesh& mesh, const Triangle& triangle, int which) { return mesh.vertices[triangle[which]]; }

Vec3 area_vector(const Mesh& mesh, const Triangle& triangle) {
  const Vec3 a = corner(mesh, triangle, 0);
  return 0.5 * (corner(mesh, triangle, 1) - a).cross(corner(mesh, triangle, 2) - a);
}

// Sum of the tetrahedra each triangle makes with the origin: positive for outward triangles.
double signed_volume(const Mesh& mesh) {
  double six_volume = 0.0;
  for (const Triangle& t : mesh.triangles) {
    six_volume += corner(mesh, t, 0).dot(corner(mesh, t, 1).cross(corner(mesh, t, 2)));
  }
  return six_volume / 6.0;
}

void translate(Mesh& mesh, const Vec3& offset) {
  for (Vec3& v : mesh.vertices) v += offset;
}

// Rounds coordinates to what the file will hold, so checks and summary describe the file.
void round_to_written_resolution(Mesh& mesh) {
  for (Vec3& v : mesh.vertices) {
    // "+ 0.0" turns -0 into +0, so no coordinate is written as "-0.0000000"
    for (int axis = 0; axis < 3; ++axis) {
      v[axis] = std::round(v[axis] / kWrittenResolution) * kWrittenResolution + 0.0;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Unit icosphere: an icosahedron whose triangles are split into four, again and again, with the
// new vertices pushed out onto the unit sphere. Its vertices are evenly spread directions.

Mesh icosahedron() {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  Mesh mesh;
  mesh.vertices = {{-1, phi, 0},  {1, phi, 0},  {-1, -phi, 0}, {1, -phi, 0}, {0, -1, phi},  {0, 1, phi},
                   {0, -1, -phi}, {0, 1, -phi}, {phi, 0, -1},  {phi, 0, 1},  {-phi, 0, -1}, {-phi, 0, 1}};
  for (Vec3& v : mesh.vertices) v.normalize();
  mesh.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                    {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  return mesh;
}

Mesh subdivided_on_unit_sphere(const Mesh& coarse) {
  Mesh fine;
  fine.vertices = coarse.vertices;
  // one midpoint per edge, shared by the two triangles on either side of it
  std::map<std::pair<int, int>, int> midpoint_of_edge;
  const auto midpoint = [&](int a, int b) {
    const std::pair<int, int> edge{std::min(a, b), std::max(a, b)};
    const auto [it, inserted] = midpoint_of_edge.emplace(edge, fine.num_vertices());
    if (inserted) {
      const Vec3 middle = fine.vertices[a] + fine.vertices[b];
      fine.vertices.push_back(middle.normalized());
    }
    return it->second;
  };
  for (const Triangle& t : coarse.triangles) {
    const int ab = midpoint(t[0], t[1]);
    const int bc = midpoint(t[1], t[2]);
    const int ca = midpoint(t[2], t[0]);
    fine.triangles.push_back({t[0], ab, ca});
    fine.triangles.push_back({t[1], bc, ab});
    fine.triangles.push_back({t[2], ca, bc});
    fine.triangles.push_back({ab, bc, ca});
  }
  return fine;
}

Mesh unit_icosphere(int subdivisions) {
  Mesh mesh = icosahedron();
  for (int level = 0; level < subdivisions; ++level) mesh = subdivided_on_unit_sphere(mesh);
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// Liver shape: a radius for every direction from the liver's centre. Moving each vertex of a
// unit icosphere out to that radius keeps the surface closed and free of self-intersections
// (it stays star-shaped about the centre) as long as the radius is positive.

double lerp(double a, double b, double t) { return a + (b - a) * t; }

double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

double liver_radius(const Vec3& direction) {
  // Where the direction meets the reference ellipsoid, in that ellipsoid's unit coordinates:
  // u runs from the left lobe's tip (-1) to the right lobe's side (+1), v from the front border
  // (-1) to the back (+1), w from the lower, visceral side (-1) to the top of the dome (+1).
  const Vec3 unit = direction.cwiseQuotient(kLiverReferenceHalfExtents).normalized();
  const double u = unit.x();
  const double v = unit.y();
  const double w = unit.z();

  // wedge: the large right lobe tapers into a thin, narrow left lobe
  const double toward_left_tip = smoothstep(-0.6, 1.0, -u);
  const double half_length = kLiverReferenceHalfExtents.x();
  const double half_width = kLiverReferenceHalfExtents.y() * lerp(1.0, 0.6, toward_left_tip);
  // dome: the upper side rises higher and rounder than the flatter lower side sinks [m]
  const double upper = smoothstep(-0.3, 0.3, w);
  const double height_above_centre = lerp(0.054, 0.022, toward_left_tip);
  const double depth_below_centre = lerp(0.032, 0.012, toward_left_tip);
  // the front border is sharper than the back
  const double border = 1.0 + 0.2 * v;
  const double half_thickness = lerp(depth_below_centre, height_above_centre, upper) * border;

  // A gauge of the direction: 1 on the surface of a superellipsoid with these (direction-
  // dependent) half extents, so the surface is reached at radius 1 / gauge. Exponent 2 would
  // make an ellipsoid; a higher one is fuller: the outline seen from above a little, the lower
  // side more (flatter) than the dome.
  const double outline_exponent = 2.5;
  const double thickness_exponent = lerp(3.0, 2.4, upper);
  const double in_plane = std::pow(std::pow(std::abs(direction.x() / half_length), outline_exponent) +
                                       std::pow(std::abs(direction.y() / half_width), outline_exponent),
                                   1.0 / outline_exponent);
  const double across = std::abs(direction.z() / half_thickness);
  const double gauge =
      std::pow(std::pow(in_plane, thickness_exponent) + std::pow(across, thickness_exponent), 1.0 / thickness_exponent);

  // a gentle notch through the front border, a little left of the middle
  const double notch_u = -0.15;
  const double notch_v = -std::sqrt(1.0 - notch_u * notch_u);
  const double from_notch_squared = std::pow(u - notch_u, 2) + std::pow(v - notch_v, 2);
  const double notch = 0.15 * std::exp(-from_notch_squared / (0.2 * 0.2));
  return (1.0 - notch) / gauge;
}

bool inside_liver(const Vec3& from_centre) {
  const double radius = from_centre.norm();
  return radius == 0.0 || radius < liver_radius(from_centre / radius);
}

// Height of the liver's surface crossing on the vertical line through `from_centre`, found by
// bisection from a point inside (`from_centre`) towards one outside (`z_outside`).
double surface_height_on_vertical(Vec3 from_centre, double z_outside) {
  double z_inside = from_centre.z();
  for (int step = 0; step < 60; ++step) {
    from_centre.z() = 0.5 * (z_inside + z_outside);
    (inside_liver(from_centre) ? z_inside : z_outside) = from_centre.z();
  }
  return 0.5 * (z_inside + z_outside);
}

// The icosphere is first stretched to the reference ellipsoid so that its vertices spread evenly
// over the long, flat liver instead of crowding its top and bottom; the stretch maps directions
// one to one, so the surface is still radial about the centre.
Mesh liver_about_its_centre() {
  Mesh mesh = unit_icosphere(kLiverSubdivisions);
  for (Vec3& v : mesh.vertices) {
    const Vec3 direction = v.cwiseProduct(kLiverReferenceHalfExtents).normalized();
    v = direction * liver_radius(direction);
  }
  return mesh;
}

struct AxisBox {
  Vec3 min;
  Vec3 max;
  Vec3 size() const { return max - min; }
};

AxisBox bounds(const Mesh& mesh) {
  AxisBox box{mesh.vertices.front(), mesh.vertices.front()};
  for (const Vec3& v : mesh.vertices) {
    box.min = box.min.cwiseMin(v);
    box.max = box.max.cwiseMax(v);
  }
  return box;
}

// ---------------------------------------------------------------------------------------------
// Tumour: an ellipsoid, centred under the probe's point a bit above mid-thickness.

Mesh tumour_at(const Vec3& centre) {
  Mesh mesh = unit_icosphere(kTumourSubdivisions);
  for (Vec3& v : mesh.vertices) v = centre + v.cwiseProduct(kTumourHalfExtents);
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// Probe: rings of vertices from the hemispherical tip (pole at the origin) up the shaft, closed
// by a fan at the tip's pole and another at the flat top cap.

struct Ring {
  double z;
  double radius;
};

std::vector<Ring> probe_rings() {
  std::vector<Ring> rings;
  for (int k = 1; k <= kProbeTipRings; ++k) {
    const double from_pole = 0.5 * kPi * k / kProbeTipRings;  // angle from the tip's pole
    rings.push_back({kProbeRadius * (1.0 - std::cos(from_pole)), kProbeRadius * std::sin(from_pole)});
  }
  for (int k = 1; k <= kProbeShaftRings; ++k) {
    rings.push_back({kProbeRadius + (kProbeLength - kProbeRadius) * k / kProbeShaftRings, kProbeRadius});
  }
  return rings;
}

Mesh probe() {
  const std::vector<Ring> rings = probe_rings();
  const int n = kProbeSegments;
  Mesh mesh;
  mesh.vertices.push_back(Vec3::Zero());  // the tip's pole
  for (const Ring& ring : rings) {
    for (int i = 0; i < n; ++i) {
      const double angle = 2.0 * kPi * i / n;
      mesh.vertices.push_back({ring.radius * std::cos(angle), ring.radius * std::sin(angle), ring.z});
    }
  }
  const int cap_centre = mesh.num_vertices();
  mesh.vertices.push_back({0.0, 0.0, kProbeLength});

  // vertex 0 is the tip's pole, then kProbeSegments vertices per ring
  const auto on_ring = [](int ring, int i) { return 1 + ring * kProbeSegments + (i % kProbeSegments); };
  const int last_ring = static_cast<int>(rings.size()) - 1;
  for (int i = 0; i < n; ++i) {
    mesh.triangles.push_back({0, on_ring(0, i + 1), on_ring(0, i)});
    for (int ring = 0; ring < last_ring; ++ring) {
      const int a = on_ring(ring, i), b = on_ring(ring, i + 1);
      const int c = on_ring(ring + 1, i + 1), d = on_ring(ring + 1, i);
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }
    mesh.triangles.push_back({cap_centre, on_ring(last_ring, i), on_ring(last_ring, i + 1)});
  }
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// Checks. Each throws with a message naming the part and the first fault found.

void require(bool condition, const std::string& message) {
  if (!condition) throw std::runtime_error(message);
}

std::string vertex_text(int index) { return "vertex " + std::to_string(index + 1); }

void check_no_duplicate_vertices(const Part& part) {
  std::set<std::array<double, 3>> seen;
  for (int i = 0; i < part.mesh.num_vertices(); ++i) {
    const Vec3& v = part.mesh.vertices[i];
    require(seen.insert({v.x(), v.y(), v.z()}).second,
            part.name + ": " + vertex_text(i) + " repeats an earlier vertex");
  }
}

void check_no_degenerate_triangles(const Part& part) {
  for (int t = 0; t < part.mesh.num_triangles(); ++t) {
    require(area_vector(part.mesh, part.mesh.triangles[t]).norm() > kMinTriangleArea,
            part.name + ": triangle " + std::to_string(t + 1) + " has (almost) no area");
  }
}

// Closed, manifold and consistently oriented: every directed edge a->b belongs to exactly one
// triangle and its reverse b->a to exactly one other, and the triangles around each vertex form
// one single fan (a disc), so no two surfaces touch at a vertex.
void check_closed_oriented_manifold(const Part& part) {
  // next_around[a][b] = c for each triangle (a, b, c) and its rotations: walking around vertex a
  // from neighbour b, the triangle on the left of a->b leads on to neighbour c
  std::vector<std::map<int, int>> next_around(part.mesh.vertices.size());
  for (const Triangle& t : part.mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k];
      const int b = t[(k + 1) % 3];
      const int c = t[(k + 2) % 3];
      require(next_around[a].emplace(b, c).second,
              part.name + ": edge " + vertex_text(a) + " -> " + vertex_text(b) +
                  " is used twice in the same direction (inconsistent orientation or non-manifold)");
    }
  }
  for (int a = 0; a < part.mesh.num_vertices(); ++a) {
    const std::string where = part.name + ": " + vertex_text(a);
    require(!next_around[a].empty(), where + " is used by no triangle");
    for (const auto& [b, c] : next_around[a]) {
      require(next_around[b].count(a) == 1,
              where + ": edge to " + vertex_text(b) + " has no triangle on its other side (a hole)");
    }
  }
  // now every walk step has a next triangle: count the steps until the walk comes back
  for (int a = 0; a < part.mesh.num_vertices(); ++a) {
    const std::map<int, int>& fan = next_around[a];
    std::size_t walked = 0;
    const int start = fan.begin()->first;
    int neighbour = start;
    do {
      neighbour = fan.at(neighbour);
      ++walked;
    } while (neighbour != start && walked <= fan.size());
    require(walked == fan.size(), part.name + ": " + vertex_text(a) + " is shared by more than one fan of triangles");
  }
}

// With the checks above, one connected piece with Euler characteristic 2 is a topological sphere.
void check_one_sphere(const Part& part) {
  const Mesh& mesh = part.mesh;
  std::vector<int> root(mesh.vertices.size());
  std::iota(root.begin(), root.end(), 0);
  const auto find = [&root](int v) {
    while (root[v] != v) v = root[v];
    return v;
  };
  for (const Triangle& t : mesh.triangles) {
    root[find(t[1])] = find(t[0]);
    root[find(t[2])] = find(t[0]);
  }
  int pieces = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v) pieces += root[v] == v ? 1 : 0;
  require(pieces == 1, part.name + ": the surface has " + std::to_string(pieces) + " separate pieces");
  // every edge is shared by two triangles: edges = 3 * triangles / 2
  const int euler = mesh.num_vertices() - 3 * mesh.num_triangles() / 2 + mesh.num_triangles();
  require(euler == 2, part.name + ": Euler characteristic " + std::to_string(euler) + ", not 2");
}

void check_positive_volume(const Part& part) {
  require(signed_volume(part.mesh) > 0.0, part.name + ": signed volume is not positive (triangles face inwards)");
}

void check_surface(const Part& part) {
  check_no_duplicate_vertices(part);
  check_no_degenerate_triangles(part);
  check_closed_oriented_manifold(part);
  check_one_sphere(part);
  check_positive_volume(part);
}

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denominator = 1.0 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

double distance_to_surface(const Vec3& p, const Mesh& surface) {
  double nearest = INFINITY;
  for (const Triangle& t : surface.triangles) {
    const Vec3 q = closest_point_on_triangle(p, corner(surface, t, 0), corner(surface, t, 1), corner(surface, t, 2));
    nearest = std::min(nearest, (p - q).norm());
  }
  return nearest;
}

// Every tumour vertex lies inside the liver, kMinTumourClearance short of its surface along the
// ray from the liver's centre, and at least that far from every liver triangle. (The tumour's
// facets lie inside its vertices' hull, and its ~2 mm edges sag far less than the margin.)
// Returns the smallest distance found.
double check_tumour_inside_liver(const Mesh& tumour, const Mesh& liver, const Vec3& liver_centre) {
  double smallest = INFINITY;
  for (int i = 0; i < tumour.num_vertices(); ++i) {
    const Vec3 from_centre = tumour.vertices[i] - liver_centre;
    const double radius = from_centre.norm();
    const std::string where = "tumour " + vertex_text(i);
    require(radius > 0.0 && radius < liver_radius(from_centre / radius) - kMinTumourClearance,
            where + " is not 1 cm inside the liver along the ray from its centre");
    const double distance = distance_to_surface(tumour.vertices[i], liver);
    require(distance >= kMinTumourClearance,
            where + " is only " + std::to_string(distance * 1000) + " mm from the liver surface");
    smallest = std::min(smallest, distance);
  }
  return smallest;
}

// ---------------------------------------------------------------------------------------------
// Writing

std::string fixed7(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.7f", value);
  return text;
}

void write_obj(const std::filesystem::path& path, const std::string& mtl_name, const std::vector<Part>& parts) {
  std::ofstream out(path, std::ios::binary);
  out << "# generated by data/generator/make_demo_meshes.cpp; units: metres\n";
  out << "mtllib " << mtl_name << "\n";
  int first_vertex = 1;  // OBJ indices are 1-based and count on across objects in the file
  for (const Part& part : parts) {
    out << "o " << part.name << "\n";
    out << "usemtl " << part.material << "\n";
    for (const Vec3& v : part.mesh.vertices) {
      out << "v " << fixed7(v.x()) << " " << fixed7(v.y()) << " " << fixed7(v.z()) << "\n";
    }
    for (const Triangle& t : part.mesh.triangles) {
      out << "f " << t[0] + first_vertex << " " << t[1] + first_vertex << " " << t[2] + first_vertex << "\n";
    }
    first_vertex += part.mesh.num_vertices();
  }
  require(!out.fail(), "cannot write " + path.string());
}

struct Material {
  std::string name;
  Vec3 diffuse;
  Vec3 specular;
  double shininess;
};

void write_mtl(const std::filesystem::path& path, const std::vector<Material>& materials) {
  std::ofstream out(path, std::ios::binary);
  out << "# generated by data/generator/make_demo_meshes.cpp\n";
  for (const Material& m : materials) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "\nnewmtl %s\nKa 0.000 0.000 0.000\nKd %.3f %.3f %.3f\nKs %.3f %.3f %.3f\nNs %.1f\n"
                  "d 1\nillum 2\n",
                  m.name.c_str(), m.diffuse.x(), m.diffuse.y(), m.diffuse.z(), m.specular.x(), m.specular.y(),
                  m.specular.z(), m.shininess);
    out << text;
  }
  require(!out.fail(), "cannot write " + path.string());
}

void print_summary(const Part& part) {
  const AxisBox box = bounds(part.mesh);
  const double volume = signed_volume(part.mesh);
  std::printf("%-7s %5zu vertices %5zu triangles  material %s\n", part.name.c_str(), part.mesh.vertices.size(),
              part.mesh.triangles.size(), part.material.c_str());
  std::printf("        box min (%.4f, %.4f, %.4f) max (%.4f, %.4f, %.4f) m\n", box.min.x(), box.min.y(), box.min.z(),
              box.max.x(), box.max.y(), box.max.z());
  std::printf("        size %.4f x %.4f x %.4f m, volume %.4e m^3 = %.4f litres (%.1f ml)\n", box.size().x(),
              box.size().y(), box.size().z(), volume, volume * 1e3, volume * 1e6);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    const std::filesystem::path output_dir = argv[1];
    std::filesystem::create_directories(output_dir);

    // The liver is shaped about its own centre, then moved to lie on the table (lowest point
    // at z = 0) with its box centred on the origin in x and y; liver_centre is where that
    // centre ends up, the point the liver is star-shaped about.
    Mesh liver = liver_about_its_centre();
    const AxisBox shaped = bounds(liver);
    const Vec3 liver_centre{-0.5 * (shaped.min.x() + shaped.max.x()), -0.5 * (shaped.min.y() + shaped.max.y()),
                            -shaped.min.z()};
    translate(liver, liver_centre);
    round_to_written_resolution(liver);

    // The tumour sits on the vertical line the probe presses along, a bit above the middle of
    // the liver's thickness there.
    const Vec3 probe_line = Vec3(kProbePointX, 0.0, 0.0) - liver_centre;
    const double top = surface_height_on_vertical({probe_line.x(), probe_line.y(), 0.0}, 1.0);
    const double bottom = surface_height_on_vertical({probe_line.x(), probe_line.y(), 0.0}, -1.0);
    const Vec3 tumour_centre{kProbePointX, 0.0, liver_centre.z() + lerp(bottom, top, kTumourHeightFraction)};
    Mesh tumour = tumour_at(tumour_centre);
    round_to_written_resolution(tumour);

    Mesh probe_mesh = probe();
    round_to_written_resolution(probe_mesh);

    const std::vector<Part> organ{{"liver", "liver_tissue", liver}, {"tumour", "tumour_tissue", tumour}};
    const std::vector<Part> instrument{{"probe", "probe_steel", probe_mesh}};
    for (const Part& part : organ) check_surface(part);
    for (const Part& part : instrument) check_surface(part);
    const double clearance = check_tumour_inside_liver(tumour, liver, liver_centre);

    write_obj(output_dir / "liver.obj", "liver.mtl", organ);
    write_mtl(output_dir / "liver.mtl", {{"liver_tissue", {0.45, 0.09, 0.07}, {0.25, 0.25, 0.25}, 40.0},
                                         {"tumour_tissue", {0.86, 0.80, 0.66}, {0.15, 0.15, 0.15}, 20.0}});
    write_obj(output_dir / "probe.obj", "probe.mtl", instrument);
    write_mtl(output_dir / "probe.mtl", {{"probe_steel", {0.62, 0.64, 0.67}, {0.80, 0.80, 0.80}, 200.0}});

    for (const Part& part : organ) print_summary(part);
    for (const Part& part : instrument) print_summary(part);
    std::printf(
        "liver at the probe point (x = %.3f, y = 0): from z = %.4f to z = %.4f m (smooth "
        "surface)\n",
        kProbePointX, liver_centre.z() + bottom, liver_centre.z() + top);
    std::printf(
        "tumour centre (%.4f, %.4f, %.4f) m; its vertices are %.1f mm or more from the "
        "liver surface\n",
        tumour_centre.x(), tumour_centre.y(), tumour_centre.z(), clearance * 1000);
    std::printf("all checks passed; wrote liver.obj, liver.mtl, probe.obj, probe.mtl in %s\n",
                output_dir.string().c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
