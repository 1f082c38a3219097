// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT

#include "calculix_beam.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#if __has_include(<sys/wait.h>)
#include <sys/wait.h>
#endif

namespace cubespring::validation {
namespace {

namespace fs = std::filesystem;

constexpr const char* kJobName = "beam";
constexpr const char* kLogName = "ccx.log";
constexpr int kLogTailLines = 12;
// above this many unknowns ccx uses its iterative solver (see build_deck)
constexpr double kIterativeAboveEquations = 100000;
constexpr double kIterativeMaxPoisson = 0.4;

// Local positions of the 20 nodes of a C3D20(R) brick on the doubled grid
// (0, 1, 2 per axis), in CalculiX/Abaqus order: corners 1-4 on the bottom
// face (z = 0) counter-clockwise seen from +z, corners 5-8 above them,
// mid-edge nodes 9-12 on the bottom edges (1-2, 2-3, 3-4, 4-1), 13-16 on the
// top edges (5-6, 6-7, 7-8, 8-5), 17-20 on the vertical edges (1-5, 2-6,
// 3-7, 4-8). Matches the natural coordinates in CalculiX's shape20h.f.
constexpr std::array<std::array<int, 3>, 20> kBrickNodes{{
    {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0},
    {0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2},
    {1, 0, 0}, {2, 1, 0}, {1, 2, 0}, {0, 1, 0},
    {1, 0, 2}, {2, 1, 2}, {1, 2, 2}, {0, 1, 2},
    {0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1},
}};

// Node ids on the doubled grid (2n+1 points per axis). Corner nodes (all
// indices even) get ids 1..corner_count in BeamReference order, so the
// corner node set is one GENERATE range and parsing needs no lookup table;
// mid-edge nodes (exactly one odd index) follow. Other points (face and
// body centres) are not nodes of a 20-node brick and keep id 0.
struct NodeGrid {
  Eigen::Vector3i n;      // elements per axis
  Eigen::Vector3i fine;   // 2n+1 points per axis
  std::vector<int> id;    // (fine.x * fine.y * fine.z), 0 = no node
  int corner_count = 0;
  int node_count = 0;

  explicit NodeGrid(const Eigen::Vector3i& elements) : n(elements) {
    fine = 2 * n + Eigen::Vector3i::Ones();
    id.assign(static_cast<std::size_t>(fine.x()) * fine.y() * fine.z(), 0);
    corner_count = (n.x() + 1) * (n.y() + 1) * (n.z() + 1);
    int next_mid = corner_count + 1;
    for (int c = 0; c < fine.z(); ++c) {
      for (int b = 0; b < fine.y(); ++b) {
        for (int a = 0; a < fine.x(); ++a) {
          const int odd = (a & 1) + (b & 1) + (c & 1);
          if (odd == 0) {
            id[index(a, b, c)] = 1 + a / 2 + (n.x() + 1) * (b / 2 + (n.y() + 1) * (c / 2));
          } else if (odd == 1) {
            id[index(a, b, c)] = next_mid++;
          }
        }
      }
    }
    node_count = next_mid - 1;
  }

  std::size_t index(int a, int b, int c) const {
    return static_cast<std::size_t>(a) + static_cast<std::size_t>(fine.x()) *
                                             (static_cast<std::size_t>(b) + static_cast<std::size_t>(fine.y()) * c);
  }
};

std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char ch : text) {
    if (ch == '\'') {
      quoted += "'\\''";
    } else {
      quoted += ch;
    }
  }
  return quoted + "'";
}

std::string format_double(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), "%.9g", value);
  return buffer;
}

// ccx reads each numeric field through its first 20 characters only
// (Fortran f20.0): longer text is cut silently, and a cut exponent is an
// input error. %.13g never exceeds 20 characters ("-1.234567890123e-100").
constexpr const char* kDeckNumber = "%.13g";

std::string deck_number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), kDeckNumber, value);
  return buffer;
}

std::string check_spec(const BeamReferenceSpec& spec) {
  for (int axis = 0; axis < 3; ++axis) {
    if (!std::isfinite(spec.size[axis]) || spec.size[axis] <= 0) {
      return "beam size must be finite and > 0 on every axis, got " + format_double(spec.size[axis]) +
             " on axis " + std::to_string(axis);
    }
    if (spec.elements[axis] < 1 || spec.elements[axis] > 4096) {
      return "elements must be in [1, 4096] on every axis, got " + std::to_string(spec.elements[axis]) +
             " on axis " + std::to_string(axis);
    }
  }
  // keep ids well inside ccx's 32-bit integers and the deck of sane size
  const double corner_estimate = (spec.elements.cast<double>() + Eigen::Vector3d::Ones()).prod();
  if (corner_estimate * 4 > 5e7) {
    return "mesh too large: " + std::to_string(spec.elements.x()) + "x" + std::to_string(spec.elements.y()) + "x" +
           std::to_string(spec.elements.z()) + " elements";
  }
  if (!std::isfinite(spec.young_modulus) || spec.young_modulus <= 0) {
    return "young_modulus must be finite and > 0 Pa, got " + format_double(spec.young_modulus);
  }
  if (!std::isfinite(spec.poisson_ratio) || spec.poisson_ratio <= -1 || spec.poisson_ratio >= 0.5) {
    return "poisson_ratio must be in (-1, 0.5), got " + format_double(spec.poisson_ratio);
  }
  if (!std::isfinite(spec.density) || spec.density <= 0) {
    return "density must be finite and > 0 kg/m^3, got " + format_double(spec.density);
  }
  if (!std::isfinite(spec.gravity)) {
    return "gravity must be finite, got " + format_double(spec.gravity);
  }
  if (spec.work_dir.empty()) {
    return "work_dir is empty; give a folder for the CalculiX deck and output";
  }
  return {};
}

std::string build_deck(const BeamReferenceSpec& spec, const NodeGrid& grid) {
  std::string deck;
  deck.reserve(static_cast<std::size_t>(grid.node_count) * 64 + static_cast<std::size_t>(spec.elements.prod()) * 140);
  deck += "** cantilever beam under gravity, written by cubespring calculix_beam.cpp\n";
  deck += "*HEADING\ncubespring cantilever beam reference\n";

  // nodes at (a, b, c) * h / 2 on the doubled grid
  const Eigen::Vector3d half_step = spec.size.cwiseQuotient(spec.elements.cast<double>()) / 2;
  deck += "*NODE, NSET=NALL\n";
  for (int c = 0; c < grid.fine.z(); ++c) {
    for (int b = 0; b < grid.fine.y(); ++b) {
      for (int a = 0; a < grid.fine.x(); ++a) {
        const int node = grid.id[grid.index(a, b, c)];
        if (node == 0) continue;
        // end points exactly on the faces, no rounding drift from a*h
        const double x = a == grid.fine.x() - 1 ? spec.size.x() : a * half_step.x();
        const double y = b == grid.fine.y() - 1 ? spec.size.y() : b * half_step.y();
        const double z = c == grid.fine.z() - 1 ? spec.size.z() : c * half_step.z();
        deck += std::to_string(node) + "," + deck_number(x) + "," + deck_number(y) + "," + deck_number(z) + "\n";
      }
    }
  }

  // ccx reads at most 16 entries per line: element id and 15 nodes, then the
  // remaining 5 nodes on a continuation line
  deck += "*ELEMENT, TYPE=C3D20R, ELSET=EALL\n";
  int element = 0;
  for (int k = 0; k < spec.elements.z(); ++k) {
    for (int j = 0; j < spec.elements.y(); ++j) {
      for (int i = 0; i < spec.elements.x(); ++i) {
        deck += std::to_string(++element);
        for (std::size_t local = 0; local < kBrickNodes.size(); ++local) {
          const auto& offset = kBrickNodes[local];
          const int node = grid.id[grid.index(2 * i + offset[0], 2 * j + offset[1], 2 * k + offset[2])];
          deck += local == 15 ? ",\n" : ",";
          deck += std::to_string(node);
        }
        deck += '\n';
      }
    }
  }

  deck += "*NSET, NSET=NCORNER, GENERATE\n1," + std::to_string(grid.corner_count) + ",1\n";

  // every node of face x = 0, corner and mid-edge alike
  deck += "*NSET, NSET=NFIX\n";
  int on_line = 0;
  for (int c = 0; c < grid.fine.z(); ++c) {
    for (int b = 0; b < grid.fine.y(); ++b) {
      const int node = grid.id[grid.index(0, b, c)];
      if (node == 0) continue;
      deck += std::to_string(node);
      deck += ++on_line == 16 ? ",\n" : ",";
      if (on_line == 16) on_line = 0;
    }
  }
  if (on_line != 0) deck += '\n';
  deck += "*BOUNDARY\nNFIX,1,3\n";

  deck += "*MATERIAL, NAME=BEAM_MATERIAL\n";
  const double e = spec.young_modulus;
  const double nu = spec.poisson_ratio;
  if (spec.nonlinear && spec.neo_hookean) {
    // compressible neo-Hookean matching the small-strain E and nu
    const double shear_modulus = e / (2 * (1 + nu));
    const double bulk_modulus = e / (3 * (1 - 2 * nu));
    deck += "*HYPERELASTIC, NEO HOOKE\n" + deck_number(shear_modulus / 2) + "," + deck_number(2 / bulk_modulus) +
            "\n";
  } else {
    deck += "*ELASTIC\n" + deck_number(e) + "," + deck_number(nu) + "\n";
  }
  deck += "*DENSITY\n" + deck_number(spec.density) + "\n";
  deck += "*SOLID SECTION, ELSET=EALL, MATERIAL=BEAM_MATERIAL\n";

  // Debian's ccx has SPOOLES (direct) and ccx's own conjugate-gradient
  // solvers, no PARDISO or PaStiX. Timed on two cores (linear step):
  //   32x8x8 (29k equations):    SPOOLES 3.4 s, ITERATIVE SCALING 3.8 s
  //   64x16x16 (215k equations): SPOOLES 90 s and 5.7 GB,
  //                              ITERATIVE SCALING 57 s and 0.4 GB
  // (ITERATIVE CHOLESKY was slower than both). The iterative answers match
  // SPOOLES to the 7 digits of the .dat output in the sag; so direct for
  // small meshes, where it is as fast and exact, iterative for large ones.
  // Near incompressibility the conjugate gradients crawl (194 s at
  // 64x16x16, nu = 0.49) while the direct solver's cost does not change.
  const double equations = 3.0 * grid.node_count;
  const bool iterative = equations > kIterativeAboveEquations && nu <= kIterativeMaxPoisson;
  const char* solver = iterative ? "ITERATIVE SCALING" : "SPOOLES";
  if (spec.nonlinear) {
    // initial increment, period, minimum and maximum increment: ccx grows or
    // cuts the increment from the convergence of each Newton solve; 0.25 took
    // 11 iterations at E = 1e5 Pa where 0.1 (max 0.25) took 16
    deck += "*STEP, NLGEOM, INC=1000\n*STATIC, SOLVER=" + std::string(solver) + "\n0.25,1.,1e-6,1.\n";
  } else {
    deck += "*STEP\n*STATIC, SOLVER=" + std::string(solver) + "\n";
  }
  deck += "*DLOAD\nEALL,GRAV," + deck_number(spec.gravity) + ",0.,0.,-1.\n";
  // .dat output: one fixed-format block per converged increment
  deck += "*NODE PRINT, NSET=NCORNER\nU\n";
  deck += "*END STEP\n";
  return deck;
}

// Reads a number as Fortran writes it, where an exponent beyond two digits
// loses its 'E' ("1.234567-100").
bool parse_fortran_double(const std::string& token, double& value) {
  if (token.empty()) return false;
  const char* begin = token.c_str();
  char* end = nullptr;
  value = std::strtod(begin, &end);
  if (end == begin) return false;
  if (*end == '\0') return true;
  if ((*end == '-' || *end == '+') && end != begin) {
    char* exponent_end = nullptr;
    const long exponent = std::strtol(end, &exponent_end, 10);
    if (exponent_end != end + 1 && *exponent_end == '\0') {
      value *= std::pow(10.0, static_cast<double>(exponent));
      return true;
    }
  }
  return false;
}

std::string read_log_tail(const fs::path& log_path) {
  std::ifstream log(log_path);
  if (!log) return "(no log at " + log_path.string() + ")";
  std::deque<std::string> tail;
  std::string line;
  while (std::getline(log, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    tail.push_back(line);
    if (static_cast<int>(tail.size()) > kLogTailLines) tail.pop_front();
  }
  if (tail.empty()) return "(log " + log_path.string() + " is empty)";
  std::string text;
  for (const auto& kept : tail) text += "\n  " + kept;
  return text;
}

// Finds the last "displacements (vx,vy,vz) for set NCORNER and time T" block
// in the .dat file; a nonlinear step writes one per converged increment.
std::string parse_dat(const fs::path& dat_path, int corner_count, std::vector<Eigen::Vector3d>& displacement,
                      double& time) {
  std::ifstream dat(dat_path);
  if (!dat) return "cannot open ccx output " + dat_path.string();
  std::vector<Eigen::Vector3d> block;
  std::vector<char> seen;
  bool in_block = false;
  bool found = false;
  std::string line;
  int line_number = 0;
  while (std::getline(dat, line)) {
    ++line_number;
    if (line.find("displacements (vx,vy,vz) for set NCORNER") != std::string::npos) {
      const std::size_t at = line.find("time");
      double block_time = NAN;
      if (at == std::string::npos) return dat_path.string() + ":" + std::to_string(line_number) + ": no time in header";
      std::istringstream header(line.substr(at + 4));
      std::string token;
      header >> token;
      if (!parse_fortran_double(token, block_time)) {
        return dat_path.string() + ":" + std::to_string(line_number) + ": unreadable time '" + token + "'";
      }
      block.assign(corner_count, Eigen::Vector3d::Constant(NAN));
      seen.assign(corner_count, 0);
      in_block = true;
      found = true;
      time = block_time;
      continue;
    }
    if (!in_block) continue;
    std::istringstream fields(line);
    std::string tokens[5];
    int count = 0;
    while (count < 5 && fields >> tokens[count]) ++count;
    // blank lines surround the data; any other line ends the block
    if (count == 0) continue;
    if (count != 4) {
      in_block = false;
      continue;
    }
    char* end = nullptr;
    const long node = std::strtol(tokens[0].c_str(), &end, 10);
    Eigen::Vector3d u;
    if (*end != '\0' || !parse_fortran_double(tokens[1], u.x()) || !parse_fortran_double(tokens[2], u.y()) ||
        !parse_fortran_double(tokens[3], u.z())) {
      return dat_path.string() + ":" + std::to_string(line_number) + ": unreadable displacement line '" + line + "'";
    }
    if (node < 1 || node > corner_count) {
      return dat_path.string() + ":" + std::to_string(line_number) + ": node " + std::to_string(node) +
             " is not a corner node (1.." + std::to_string(corner_count) + ")";
    }
    block[node - 1] = u;
    seen[node - 1] = 1;
  }
  if (!found) return dat_path.string() + ": no displacement block for set NCORNER";
  for (int node = 0; node < corner_count; ++node) {
    if (!seen[node]) {
      return dat_path.string() + ": last displacement block lacks node " + std::to_string(node + 1);
    }
    if (!block[node].allFinite()) {
      return dat_path.string() + ": non-finite displacement at node " + std::to_string(node + 1);
    }
  }
  displacement = block;
  return {};
}

BeamResult fail(std::string message) {
  BeamResult result;
  result.error = std::move(message);
  return result;
}

BeamResult compute(const BeamReferenceSpec& spec) {
  if (std::string problem = check_spec(spec); !problem.empty()) return fail("calculix beam: " + problem);
  if (!calculix_available()) {
    return fail("calculix beam: ccx not found on PATH (install Debian's calculix-ccx)");
  }

  // work folder, cleared of the outputs of an earlier run so a failed run
  // can never be mistaken for a good one
  std::error_code ec;
  // absolute, so the shell's cd can never take it for an option
  const fs::path work_dir = fs::absolute(fs::path(spec.work_dir), ec);
  if (ec) return fail("calculix beam: bad work_dir " + spec.work_dir + ": " + ec.message());
  fs::create_directories(work_dir, ec);
  if (ec || !fs::is_directory(work_dir)) {
    return fail("calculix beam: cannot create work_dir " + work_dir.string() + ": " +
                (ec ? ec.message() : std::string("not a directory")));
  }
  const fs::path inp_path = work_dir / (std::string(kJobName) + ".inp");
  const fs::path dat_path = work_dir / (std::string(kJobName) + ".dat");
  const fs::path log_path = work_dir / kLogName;
  fs::remove(dat_path, ec);
  fs::remove(log_path, ec);

  const NodeGrid grid(spec.elements);
  {
    std::ofstream inp(inp_path, std::ios::binary | std::ios::trunc);
    if (!inp) return fail("calculix beam: cannot write " + inp_path.string());
    inp << build_deck(spec, grid);
    inp.close();
    if (!inp) return fail("calculix beam: error writing " + inp_path.string());
  }

  // OMP_NUM_THREADS sets ccx's threads for assembly and SPOOLES (4.1 s with
  // one, 3.4 s with two at 32x8x8); the project's machines have two cores
  const std::string command = "cd " + shell_quote(work_dir.string()) + " && OMP_NUM_THREADS=2 ccx -i " + kJobName +
                              " </dev/null >" + kLogName + " 2>&1";
  const int status = std::system(command.c_str());
  if (status != 0) {
    std::string how = "status " + std::to_string(status);
#if __has_include(<sys/wait.h>)
    if (status == -1) {
      how = "could not start a shell";
    } else if (WIFEXITED(status)) {
      how = "exit code " + std::to_string(WEXITSTATUS(status));
    } else if (WIFSIGNALED(status)) {
      how = "signal " + std::to_string(WTERMSIG(status));
    }
#endif
    return fail("calculix beam: ccx failed (" + how + ") in " + work_dir.string() + "; last lines of " +
                log_path.string() + ":" + read_log_tail(log_path));
  }

  BeamReference reference;
  reference.elements = spec.elements;
  reference.size = spec.size;
  double time = NAN;
  if (std::string problem = parse_dat(dat_path, grid.corner_count, reference.corner_displacement, time);
      !problem.empty()) {
    return fail("calculix beam: " + problem + "; last lines of " + log_path.string() + ":" +
                read_log_tail(log_path));
  }
  // the step's period is 1: an earlier time means ccx stopped short
  if (!(std::abs(time - 1.0) < 1e-6)) {
    return fail("calculix beam: last displacement block in " + dat_path.string() + " is at time " +
                format_double(time) + ", not at the end of the step (1); last lines of " + log_path.string() + ":" +
                read_log_tail(log_path));
  }
  BeamResult result;
  result.reference = std::move(reference);
  return result;
}

}  // namespace

std::optional<Eigen::Vector3d> BeamReference::displacement_at(const Eigen::Vector3d& rest_point) const {
  const Eigen::Vector3i n = elements;
  if ((n.array() < 1).any() || !size.allFinite() || (size.array() <= 0).any()) return std::nullopt;
  if (corner_displacement.size() != static_cast<std::size_t>((n.x() + 1) * (n.y() + 1) * (n.z() + 1))) {
    return std::nullopt;
  }
  if (!rest_point.allFinite()) return std::nullopt;
  const double tolerance = 1e-9 * size.maxCoeff();
  std::array<int, 3> index{};
  for (int axis = 0; axis < 3; ++axis) {
    const double step = size[axis] / n[axis];
    const double nearest = std::round(rest_point[axis] / step);
    if (nearest < 0 || nearest > n[axis]) return std::nullopt;
    const double snapped = nearest == n[axis] ? size[axis] : nearest * step;
    if (std::abs(rest_point[axis] - snapped) > tolerance) return std::nullopt;
    index[axis] = static_cast<int>(nearest);
  }
  return corner_displacement[index[0] + (n.x() + 1) * (index[1] + (n.y() + 1) * index[2])];
}

double BeamReference::tip_deflection() const {
  const Eigen::Vector3i n = elements;
  if ((n.array() < 1).any() ||
      corner_displacement.size() != static_cast<std::size_t>((n.x() + 1) * (n.y() + 1) * (n.z() + 1))) {
    return NAN;
  }
  double sum = 0;
  for (int k = 0; k <= n.z(); ++k) {
    for (int j = 0; j <= n.y(); ++j) {
      sum += corner_displacement[n.x() + (n.x() + 1) * (j + (n.y() + 1) * k)].z();
    }
  }
  return sum / ((n.y() + 1) * (n.z() + 1));
}

BeamResult compute_beam_reference(const BeamReferenceSpec& spec) {
  // filesystem and allocation failures must come back as messages too
  try {
    return compute(spec);
  } catch (const std::exception& error) {
    return fail(std::string("calculix beam: unexpected failure: ") + error.what());
  } catch (...) {
    return fail("calculix beam: unexpected failure");
  }
}

bool calculix_available() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  std::string entries(path);
  std::size_t start = 0;
  while (start <= entries.size()) {
    std::size_t end = entries.find(':', start);
    if (end == std::string::npos) end = entries.size();
    // an empty PATH entry means the current directory
    const std::string dir = end == start ? "." : entries.substr(start, end - start);
    std::error_code ec;
    const fs::path candidate = fs::path(dir) / "ccx";
    const fs::file_status status = fs::status(candidate, ec);
    if (!ec && fs::is_regular_file(status) &&
        (status.permissions() & (fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec)) !=
            fs::perms::none) {
      return true;
    }
    start = end + 1;
  }
  return false;
}

}  // namespace cubespring::validation
