// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "indentation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include <gtest/gtest.h>

#include "calculix_common.h"

namespace cubespring::validation {
namespace {

// The model (its reasons):
// - a quarter of the block, x >= 0 and y >= 0, the planes x = 0 and y = 0 held along their normal:
//   the case is symmetric about both, and a quarter has a quarter of the unknowns;
// - C3D20R bricks on a tensor grid, uniform within 10 mm of the axis and of the top (the contact
//   radius is about 8 mm at 10 mm deep) and growing by 1.5 beyond: quadratic faces follow the sphere
//   and are what ccx's surface-to-surface contact is made for; ccx's cost is its direct solve, about
//   (unknowns)^2 per Newton iteration, and a tensor grid refines every row the fine zone crosses, so
//   the zone is kept small and the growth steep (12 mm growing by 1.3 at 2 mm took 2.4 times the
//   elements and 3 times the time of 10 mm growing by 1.5 at 2.5 mm, for forces within 0.35%);
// - the sphere a quarter of the lower hemisphere of C3D20 bricks (one radial layer, the octant as
//   the three faces of a cube projected on it, at half the block's fine size), every node of it
//   moved by the same prescribed displacement: a rigid sphere that only translates, as *RIGID BODY
//   would make it but without its constraint equations; its force is its nodes' summed reaction,
//   which the base's must balance (both are printed, and checked);
// - surface-to-surface contact, frictionless (no *FRICTION), linear penalty: the block's top faces
//   near the axis are the slave surface, the sphere's outer faces the master (tried the other way
//   round: no faster);
// - the sphere's travel ramped over one step with automatic increments (at most 0.25 mm), the results
//   printed at the depths' times (*TIME POINTS).
constexpr const char* kJob = "indentation";
constexpr double kFineLength = 0.010;   // the fine zone along x, y and down from the top [m]
constexpr double kGrowth = 1.5;         // element size ratio beyond it
constexpr double kSlaveExtent = 0.018;  // the slave faces, x and y below this [m]
constexpr double kSphereLayer = 0.2;    // the sphere's layer, a fraction of its radius
// pressure per overlap [Pa/m]: 1e9 left the top face's nodes 12-33 um inside the sphere (0.6% of the
// depth, about 1% of the force: F ~ d^1.5); 1e10 left 2 um or less but took 10 Newton iterations an
// increment where 1e9 took 5, and diverged 8 mm deep on the 1.67 mm mesh with 0.5 mm increments;
// 3e9 leaves 10 um or less (0.2% of the depth: the CSV's penetration_m) and forces within 0.2% of
// 1e10's (2.5 mm mesh)
constexpr double kPenaltyStiffness = 3e9;
// a top-face node touches the sphere when it is within this of its surface [m]
constexpr double kTouching = 1e-5;

constexpr const char* kAbout =
    "# A rigid frictionless sphere, R 10 mm, pressed depth_m (from first touch) into the centre of the top of a\n"
    "# 10 x 10 x 5 cm block, E 5 kPa, nu 0.45, its base bonded, the rest free, no gravity. CalculiX 2.20 NLGEOM,\n"
    "# *HYPERELASTIC, NEO HOOKE (C10 = E / (4 (1 + nu)), D1 = 6 (1 - 2 nu) / E).\n"
    "# Model (reasons in tests/validation/indentation.cpp): a quarter of the block by symmetry (x, y >= 0, the\n"
    "# planes x = 0 and y = 0 held along their normals); C3D20R (quadratic faces, for ccx's surface-to-surface\n"
    "# contact) on a tensor grid, 10 mm / (mesh_level + 2) within 10 mm of the axis and of the top (the contact\n"
    "# radius is about 8 mm at 10 mm deep), growing by 1.5 beyond; the sphere a quarter hemisphere of C3D20 whose\n"
    "# every node is moved by -depth (rigid and translating, without *RIGID BODY's equations); SURFACE TO SURFACE\n"
    "# contact, frictionless, linear penalty 3e9 Pa/m (penetration_m), the block's top the slave; the depths are\n"
    "# time points of one step of automatic increments. The finest two meshes show the convergence.\n"
    "# force_N: the block's push on the sphere along z (4 x minus its nodes' summed reaction); base_force_N: 4 x the\n"
    "# base's reaction (equilibrium: the same); contact_radius_m: rest x of the last top-face corner node on y = 0\n"
    "# within 10 um of the sphere (to a node); penetration_m: their largest overlap with the sphere.\n"
    "# Made by tests/validation/test_indentation_reference.cpp (label reference): ctest --test-dir build/release\n"
    "# -R IndentationReference --output-on-failure, then copy the file it names over this one.\n";

double fine_size(int mesh_level) { return kFineLength / (mesh_level + 2); }

// Corners along an axis of length `length` from 0: uniform up to kFineLength, then growing by
// kGrowth, the growing part scaled to end at `length`.
std::vector<double> graded_axis(double length, double h) {
  const int fine = static_cast<int>(std::ceil(kFineLength / h - 1e-9));
  std::vector<double> x;
  for (int i = 0; i <= fine; ++i) x.push_back(kFineLength * i / fine);
  const double rest = length - kFineLength;
  std::vector<double> sizes;
  double sum = 0, size = kFineLength / fine;
  while (sum < rest) {
    size *= kGrowth;
    // stop where the sum is nearest to the rest
    if (sum + size > rest && sum + size - rest > rest - sum && !sizes.empty()) break;
    sizes.push_back(size);
    sum += size;
  }
  for (const double s : sizes) x.push_back(x.back() + s * rest / sum);
  x.back() = length;
  return x;
}

struct Node {
  int id;
  std::array<double, 3> x;
};

struct Mesh {
  std::vector<Node> nodes;
  std::string elements;  // *ELEMENT blocks
  int block_elements = 0;
  int corner_line = 0;         // corners on the top face at y = 0: ids 1..corner_line, x growing
  std::vector<double> line_x;  // their rest x
  std::vector<int> base, symmetry_x, symmetry_y, sphere;
  std::vector<int> slave_elements, master_elements;
};

std::string element_line(int id, const std::array<int, 20>& nodes) {
  std::string line = std::to_string(id);
  for (int local = 0; local < 20; ++local) {
    line += local == 15 ? ",\n" : ",";
    line += std::to_string(nodes[local]);
  }
  return line + "\n";
}

// The block's C3D20R mesh: corner nodes first, numbered from the top face down (node 1 on the axis
// at the top), x fastest; mid-edge nodes after them.
void mesh_block(int mesh_level, Mesh& mesh) {
  const double h = fine_size(mesh_level);
  const double half = kIndentationSide / 2;
  const std::vector<double> xs = graded_axis(half, h);
  std::vector<double> zs = graded_axis(kIndentationThickness, h);  // depths from the top
  for (double& z : zs) z = kIndentationThickness - z;
  std::reverse(zs.begin(), zs.end());  // heights from the base
  const int nx = static_cast<int>(xs.size()) - 1, nz = static_cast<int>(zs.size()) - 1;
  const int fx = 2 * nx + 1, fz = 2 * nz + 1;
  auto coordinate = [](const std::vector<double>& corners, int a) {
    return a % 2 == 0 ? corners[a / 2] : (corners[a / 2] + corners[a / 2 + 1]) / 2;
  };
  auto at = [&](int a, int b, int c) { return static_cast<std::size_t>(a + fx * (b + fx * c)); };
  std::vector<int> id(static_cast<std::size_t>(fx) * fx * fz, 0);
  int next = (nx + 1) * (nx + 1) * (nz + 1) + 1;
  for (int c = 0; c < fz; ++c) {
    for (int b = 0; b < fx; ++b) {
      for (int a = 0; a < fx; ++a) {
        const int odd = a % 2 + b % 2 + c % 2;
        if (odd > 1) continue;
        const int node = odd == 0 ? 1 + a / 2 + (nx + 1) * (b / 2 + (nx + 1) * (nz - c / 2)) : next++;
        id[at(a, b, c)] = node;
        mesh.nodes.push_back({node, {coordinate(xs, a), coordinate(xs, b), coordinate(zs, c)}});
        if (c == 0) mesh.base.push_back(node);
        if (a == 0) mesh.symmetry_x.push_back(node);
        if (b == 0) mesh.symmetry_y.push_back(node);
      }
    }
  }
  mesh.corner_line = nx + 1;
  mesh.line_x = xs;
  mesh.elements += "*ELEMENT, TYPE=C3D20R, ELSET=BLOCK\n";
  int element = 0;
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < nx; ++j) {
      for (int i = 0; i < nx; ++i) {
        std::array<int, 20> nodes{};
        for (int local = 0; local < 20; ++local) {
          const auto& o = kBrickNodes[local];
          nodes[local] = id[at(2 * i + o[0], 2 * j + o[1], 2 * k + o[2])];
        }
        mesh.elements += element_line(++element, nodes);
        if (k == nz - 1 && xs[i] < kSlaveExtent && xs[j] < kSlaveExtent) mesh.slave_elements.push_back(element);
      }
    }
  }
  mesh.block_elements = element;
}

// The sphere's quarter lower hemisphere, centred at rest on the axis a radius above the top face:
// the octant x, y >= 0, z <= 0 (about the centre) is the three cube faces z = -1, x = 1, y = 1
// projected on the sphere, each an n x n grid (equal angles), one radial layer of C3D20 bricks
// whose outer face is their face 2.
void mesh_sphere(int mesh_level, Mesh& mesh) {
  const double r = kIndentationRadius;
  const std::array<double, 3> centre{0, 0, kIndentationThickness + r};
  const double pi = 3.14159265358979323846;
  // patch edges are quarter arcs of the 45-degree arc: about half the block's fine size
  const int n = static_cast<int>(std::ceil(pi / 4 * r / (fine_size(mesh_level) / 2)));
  std::map<std::tuple<long, long, long>, int> ids;
  int next = 0;
  for (const Node& node : mesh.nodes) next = std::max(next, node.id);
  ++next;
  auto node_at = [&](std::array<double, 3> cube, double radius) {
    const double length = std::sqrt(cube[0] * cube[0] + cube[1] * cube[1] + cube[2] * cube[2]);
    std::array<double, 3> x{};
    for (int d = 0; d < 3; ++d) x[d] = centre[d] + radius * cube[d] / length;
    const std::tuple<long, long, long> key{std::lround(x[0] * 1e8), std::lround(x[1] * 1e8), std::lround(x[2] * 1e8)};
    auto found = ids.find(key);
    if (found != ids.end()) return found->second;
    ids[key] = next;
    mesh.nodes.push_back({next, x});
    mesh.sphere.push_back(next);
    return next++;
  };
  // a cube face point from two parameters in [0, 1]
  auto patch = [&](int p, double u, double v) -> std::array<double, 3> {
    const double s = std::tan(u * pi / 4), t = std::tan(v * pi / 4);
    if (p == 0) return {s, t, -1};
    if (p == 1) return {1, s, -t};
    return {s, 1, -t};
  };
  mesh.elements += "*ELEMENT, TYPE=C3D20, ELSET=SPHERE\n";
  int element = mesh.block_elements;
  for (int p = 0; p < 3; ++p) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        // local (x, y) along the parameters, local z outwards; flip y where that turns left-handed
        auto corner = [&](int a, int b) { return patch(p, (2 * i + a) / (2.0 * n), (2 * j + b) / (2.0 * n)); };
        const std::array<double, 3> o = corner(0, 0), du = corner(2, 0), dv = corner(0, 2);
        std::array<double, 3> e1{}, e2{};
        for (int d = 0; d < 3; ++d) {
          e1[d] = du[d] - o[d];
          e2[d] = dv[d] - o[d];
        }
        const double outward = (e1[1] * e2[2] - e1[2] * e2[1]) * o[0] + (e1[2] * e2[0] - e1[0] * e2[2]) * o[1] +
                               (e1[0] * e2[1] - e1[1] * e2[0]) * o[2];
        std::array<int, 20> nodes{};
        for (int local = 0; local < 20; ++local) {
          const auto& q = kBrickNodes[local];
          const int b = outward > 0 ? q[1] : 2 - q[1];
          const double radius = r * (1 - kSphereLayer * (1 - q[2] / 2.0));
          nodes[local] = node_at(corner(q[0], b), radius);
        }
        mesh.elements += element_line(++element, nodes);
        mesh.master_elements.push_back(element);
      }
    }
  }
}

std::string node_set(const char* name, const std::vector<int>& nodes) {
  std::string set = std::string("*NSET, NSET=") + name + "\n";
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    set += std::to_string(nodes[n]);
    set += (n + 1) % 16 == 0 || n + 1 == nodes.size() ? "\n" : ",";
  }
  return set;
}

std::string face_surface(const char* name, const std::vector<int>& elements, int face) {
  std::string surface = std::string("*SURFACE, NAME=") + name + ", TYPE=ELEMENT\n";
  for (const int element : elements) surface += std::to_string(element) + ",S" + std::to_string(face) + "\n";
  return surface;
}

Mesh make_mesh(int mesh_level) {
  if (mesh_level < 1 || mesh_level > 8) {
    throw std::invalid_argument("indentation: mesh_level must be in [1, 8], got " + std::to_string(mesh_level));
  }
  Mesh mesh;
  mesh_block(mesh_level, mesh);
  mesh_sphere(mesh_level, mesh);
  return mesh;
}

std::string deck_for(const Mesh& mesh) {
  const double deepest = kIndentationDepths.back();
  std::string deck;
  deck += "** sphere indentation, quarter model, written by cubespring tests/validation/indentation.cpp\n";
  deck += "*HEADING\ncubespring sphere indentation\n*NODE, NSET=NALL\n";
  for (const Node& node : mesh.nodes) {
    deck += std::to_string(node.id) + "," + deck_number(node.x[0]) + "," + deck_number(node.x[1]) + "," +
            deck_number(node.x[2]) + "\n";
  }
  deck += mesh.elements;
  deck += "*NSET, NSET=NCORNER, GENERATE\n1," + std::to_string(mesh.corner_line) + ",1\n";
  deck += node_set("NBASE", mesh.base) + node_set("NSYMX", mesh.symmetry_x) + node_set("NSYMY", mesh.symmetry_y) +
          node_set("NSPHERE", mesh.sphere);
  deck += face_surface("STOP", mesh.slave_elements, 2) + face_surface("SSPHERE", mesh.master_elements, 2);

  // C10 = G / 2, D1 = 2 / K, as bonded_compression (calculix_beam.cpp)
  const double e = kIndentationYoung, nu = kIndentationPoisson;
  deck += "*MATERIAL, NAME=TISSUE\n*HYPERELASTIC, NEO HOOKE\n" + deck_number(e / (4 * (1 + nu))) + "," +
          deck_number(6 * (1 - 2 * nu) / e) + "\n";
  deck += "*SOLID SECTION, ELSET=BLOCK, MATERIAL=TISSUE\n";
  // the sphere's nodes are all prescribed: its material carries nothing
  deck += "*MATERIAL, NAME=RIGID\n*ELASTIC\n" + deck_number(1000 * e) + ",0.3\n";
  deck += "*SOLID SECTION, ELSET=SPHERE, MATERIAL=RIGID\n";

  deck += "*SURFACE INTERACTION, NAME=FRICTIONLESS\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n" +
          deck_number(kPenaltyStiffness) + "\n";
  deck += "*CONTACT PAIR, INTERACTION=FRICTIONLESS, TYPE=SURFACE TO SURFACE\nSTOP,SSPHERE\n";
  deck += "*BOUNDARY\nNBASE,1,3\nNSYMX,1,1\nNSYMY,2,2\nNSPHERE,1,2\n";

  deck += "*TIME POINTS, NAME=DEPTHS\n";
  for (std::size_t d = 0; d < kIndentationDepths.size(); ++d) {
    deck += deck_number(kIndentationDepths[d] / deepest) + (d + 1 == kIndentationDepths.size() ? "\n" : ",");
  }
  // initial increment, period, minimum and maximum increment
  deck += "*STEP, NLGEOM, INC=10000\n*STATIC\n0.01,1.,1e-6,0.025\n";
  deck += "*BOUNDARY\nNSPHERE,3,3," + deck_number(-deepest) + "\n";
  deck += "*NODE PRINT, NSET=NSPHERE, TOTALS=ONLY, TIME POINTS=DEPTHS\nRF\n";
  deck += "*NODE PRINT, NSET=NBASE, TOTALS=ONLY, TIME POINTS=DEPTHS\nRF\n";
  deck += "*NODE PRINT, NSET=NCORNER, TIME POINTS=DEPTHS\nU\n";
  deck += "*END STEP\n";
  return deck;
}

bool parse_number(const std::string& token, double& value) {
  // ccx prints three-digit exponents without the E ("1.0-100")
  char* end = nullptr;
  value = std::strtod(token.c_str(), &end);
  if (end == token.c_str()) return false;
  if (*end == '\0') return true;
  if (*end == '-' || *end == '+') {
    char* exponent_end = nullptr;
    const long exponent = std::strtol(end, &exponent_end, 10);
    if (*exponent_end == '\0') {
      value *= std::pow(10.0, static_cast<double>(exponent));
      return true;
    }
  }
  return false;
}

// What the .dat prints at one time: the summed reactions of NSPHERE and NBASE, the displacements
// of the top line's corners (node id - 1).
struct Printed {
  std::array<double, 3> sphere{NAN, NAN, NAN}, base{NAN, NAN, NAN};
  std::vector<std::array<double, 3>> line;
};

std::map<double, Printed> read_dat(const std::string& path, int line_nodes) {
  std::ifstream dat(path);
  if (!dat) throw std::runtime_error("indentation: cannot open ccx output " + path);
  std::map<double, Printed> printed;
  std::string line, what;
  Printed* at = nullptr;
  int line_number = 0;
  auto fail = [&](const std::string& message) {
    return std::runtime_error("indentation: " + path + ":" + std::to_string(line_number) + ": " + message);
  };
  while (std::getline(dat, line)) {
    ++line_number;
    const bool force = line.find("total force (fx,fy,fz) for set ") != std::string::npos;
    const bool displacement = line.find("displacements (vx,vy,vz) for set NCORNER") != std::string::npos;
    if (force || displacement) {
      const std::size_t time_at = line.find("and time");
      double time = NAN;
      std::istringstream header(time_at == std::string::npos ? std::string() : line.substr(time_at + 8));
      std::string token;
      header >> token;
      if (!parse_number(token, time)) throw fail("no time in '" + line + "'");
      // the printed times are the depths' fractions of the deepest, to 7 digits
      at = &printed[std::round(time * 1e6) / 1e6];
      if (displacement) {
        what = "U";
        at->line.assign(line_nodes, {NAN, NAN, NAN});
      } else {
        std::istringstream fields(line.substr(line.find("for set ") + 8));
        fields >> what;
      }
      continue;
    }
    if (at == nullptr) continue;
    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string token; fields >> token;) tokens.push_back(token);
    if (tokens.empty()) continue;
    if (what == "U" && tokens.size() == 4) {
      const int node = std::atoi(tokens[0].c_str());
      if (node < 1 || node > line_nodes) throw fail("node " + tokens[0] + " is not on the top line");
      for (int d = 0; d < 3; ++d) {
        if (!parse_number(tokens[1 + d], at->line[node - 1][d])) throw fail("unreadable '" + line + "'");
      }
      continue;
    }
    if ((what == "NSPHERE" || what == "NBASE") && tokens.size() == 3) {
      std::array<double, 3>& total = what == "NSPHERE" ? at->sphere : at->base;
      for (int d = 0; d < 3; ++d) {
        if (!parse_number(tokens[d], total[d])) throw fail("unreadable '" + line + "'");
      }
    }
    at = nullptr;
  }
  return printed;
}

}  // namespace

std::string indentation_deck(int mesh_level) { return deck_for(make_mesh(mesh_level)); }

std::vector<IndentationRow> solve_indentation_with_calculix(int mesh_level, const std::string& work_dir) {
  const Mesh mesh = make_mesh(mesh_level);
  // run_ccx checks that the step ran to its end (the top line printed at time 1)
  const CcxResult run = run_ccx(work_dir, kJob, deck_for(mesh), mesh.corner_line);
  if (!run.error.empty())
    throw std::runtime_error("indentation, mesh level " + std::to_string(mesh_level) + ": " + run.error);
  const std::string dat = (std::filesystem::absolute(work_dir) / (std::string(kJob) + ".dat")).string();
  const std::map<double, Printed> printed = read_dat(dat, mesh.corner_line);
  const double deepest = kIndentationDepths.back();
  std::vector<IndentationRow> rows;
  for (const double depth : kIndentationDepths) {
    auto found = printed.find(std::round(depth / deepest * 1e6) / 1e6);
    if (found == printed.end()) {
      throw std::runtime_error("indentation: " + dat + " has nothing at depth " + format_double(depth) + " m");
    }
    const Printed& p = found->second;
    if (!std::isfinite(p.sphere[2]) || !std::isfinite(p.base[2]) ||
        static_cast<int>(p.line.size()) != mesh.corner_line) {
      throw std::runtime_error("indentation: " + dat + " lacks a total force or the top line at depth " +
                               format_double(depth) + " m");
    }
    IndentationRow row;
    row.depth = depth;
    row.mesh_level = mesh_level;
    row.elements = mesh.block_elements;
    // the quarter's reactions: the sphere's nodes are pushed up (the block's force on the sphere is
    // minus their reaction), the base's down
    row.force = -4 * p.sphere[2];
    row.base_force = 4 * p.base[2];
    // the top line against the sphere, centred a radius above the top face less the depth
    const double centre = kIndentationThickness + kIndentationRadius - depth;
    for (int n = 0; n < mesh.corner_line; ++n) {
      const std::array<double, 3>& u = p.line[n];
      if (!std::isfinite(u[0]) || !std::isfinite(u[2])) {
        throw std::runtime_error("indentation: " + dat + " lacks node " + std::to_string(n + 1));
      }
      const double overlap =
          kIndentationRadius - std::hypot(mesh.line_x[n] + u[0], kIndentationThickness + u[2] - centre);
      row.penetration = std::max(row.penetration, overlap);
      if (overlap > -kTouching) row.contact_radius = mesh.line_x[n];
    }
    rows.push_back(row);
  }
  return rows;
}

std::vector<IndentationRow> read_indentation_rows(const std::string& path) {
  std::vector<IndentationRow> rows;
  std::ifstream in(path);
  if (!in) ADD_FAILURE() << "cannot open " << path;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("depth", 0) == 0) continue;
    // depth_m,mesh_level,elements,force_N,base_force_N,contact_radius_m,penetration_m
    std::istringstream fields(line);
    IndentationRow row;
    char c[6] = {};
    fields >> row.depth >> c[0] >> row.mesh_level >> c[1] >> row.elements >> c[2] >> row.force >> c[3] >>
        row.base_force >> c[4] >> row.contact_radius >> c[5] >> row.penetration;
    if (!fields || std::string(c, 6) != ",,,,,,") {
      ADD_FAILURE() << path << ": cannot read the line '" << line << "'";
      continue;
    }
    rows.push_back(row);
  }
  return rows;
}

void write_indentation_rows(const std::vector<IndentationRow>& rows, const std::string& path) {
  std::ofstream out(path);
  out << kAbout << "depth_m,mesh_level,elements,force_N,base_force_N,contact_radius_m,penetration_m\n";
  char line[200];
  for (const IndentationRow& row : rows) {
    std::snprintf(line, sizeof line, "%.4f,%d,%d,%.9e,%.9e,%.4e,%.4e\n", row.depth, row.mesh_level, row.elements,
                  row.force, row.base_force, row.contact_radius, row.penetration);
    out << line;
  }
}

}  // namespace cubespring::validation
