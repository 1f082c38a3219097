// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Reading CalculiX .frd results, and comparing a cantilever with a finite-element solution.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "cubespring/validation/calculix_result.h"
#include "cubespring/validation/fem_comparison.h"

namespace cubespring {
namespace {

const std::string kOneBrick = std::string(CUBESPRING_TEST_DATA_DIR) + "/calculix/one_brick.frd";

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

// The volume a closed surface encloses (divergence theorem): positive when it faces outward.
double enclosed_volume(const FemSolution& fem) {
  double volume = 0;
  for (Eigen::Index t = 0; t < fem.surface.cols(); ++t) {
    const Eigen::Vector3d a = fem.rest_positions.col(fem.surface(0, t));
    const Eigen::Vector3d b = fem.rest_positions.col(fem.surface(1, t));
    const Eigen::Vector3d c = fem.rest_positions.col(fem.surface(2, t));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

// A result in the .frd layout the CalculiX GraphiX manual gives (long format: I10 numbers, E12.5
// values), written here so that tests can make shapes ccx was not run on.
struct FrdElement {
  int type;
  std::vector<int> nodes;
};
std::string frd_text(const std::vector<Eigen::Vector3d>& nodes, const std::vector<FrdElement>& elements,
                     const std::vector<Eigen::Vector3d>& displacements) {
  std::string text = "    1C\n";
  char line[256];
  std::snprintf(line, sizeof line, "    2C%26zu%37d\n", nodes.size(), 1);
  text += line;
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    std::snprintf(line, sizeof line, " -1%10zu%12.5E%12.5E%12.5E\n", n + 1, nodes[n].x(), nodes[n].y(), nodes[n].z());
    text += line;
  }
  text += " -3\n";
  std::snprintf(line, sizeof line, "    3C%26zu%37d\n", elements.size(), 1);
  text += line;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    std::snprintf(line, sizeof line, " -1%10zu%5d%5d%5d\n", e + 1, elements[e].type, 0, 1);
    text += line;
    for (std::size_t k = 0; k < elements[e].nodes.size(); k += 10) {
      text += " -2";
      for (std::size_t j = k; j < std::min(k + 10, elements[e].nodes.size()); ++j) {
        std::snprintf(line, sizeof line, "%10d", elements[e].nodes[j]);
        text += line;
      }
      text += "\n";
    }
  }
  text += " -3\n -4  DISP        4    1\n -5  D1          1    2    1    0\n";
  for (std::size_t n = 0; n < displacements.size(); ++n) {
    const Eigen::Vector3d& u = displacements[n];
    std::snprintf(line, sizeof line, " -1%10zu%12.5E%12.5E%12.5E\n", n + 1, u.x(), u.y(), u.z());
    text += line;
  }
  return text + " -3\n 9999\n";
}

TEST(CalculixResult, ReadsWhatCcxWroteForOneBrick) {
  // tests/data/calculix/one_brick.inp: a 1 cm C3D8 cube held at x = 0 under gravity, run by ccx 2.20
  Result<FemSolution> read = read_calculix_frd(kOneBrick);
  ASSERT_TRUE(read) << read.message();
  const FemSolution& fem = read.value();
  ASSERT_EQ(fem.node_ids.size(), 8u);
  EXPECT_EQ(fem.node_ids[1], 2);
  EXPECT_TRUE(fem.rest_positions.col(6).isApprox(Eigen::Vector3d(0.01, 0.01, 0.01)));
  EXPECT_TRUE(fem.displacements.col(1).isApprox(Eigen::Vector3d(-9.23074e-07, -2.18623e-07, -2.19837e-06)));
  EXPECT_TRUE(fem.displacements.col(0).isZero());
  EXPECT_EQ(fem.surface.cols(), 12);  // six faces, two triangles each
  EXPECT_NEAR(enclosed_volume(fem), 1e-6, 1e-12);
}

TEST(CalculixResult, OnlyFacesThatNoOtherElementSharesAreSurface) {
  // two bricks side by side along x (the shared face is inside), and the same as tetrahedra
  std::vector<Eigen::Vector3d> nodes;
  for (int z = 0; z < 2; ++z) {
    for (int y = 0; y < 2; ++y) {
      for (int x = 0; x < 3; ++x) nodes.emplace_back(x, y, z);
    }
  }
  const auto id = [](int x, int y, int z) { return 1 + x + 3 * (y + 2 * z); };
  // the second brick lists its top face first: a mirror image of the frd order, which a reader
  // that trusts the order would turn inside out
  std::vector<FrdElement> bricks;
  for (int x = 0; x < 2; ++x) {
    const int low = x == 0 ? 0 : 1;
    const int high = 1 - low;
    bricks.push_back({1,
                      {id(x, 0, low), id(x + 1, 0, low), id(x + 1, 1, low), id(x, 1, low), id(x, 0, high),
                       id(x + 1, 0, high), id(x + 1, 1, high), id(x, 1, high)}});
  }
  const std::vector<Eigen::Vector3d> still(nodes.size(), Eigen::Vector3d::Zero());
  Result<FemSolution> two = read_calculix_frd(write_temp("two_bricks.frd", frd_text(nodes, bricks, still)));
  ASSERT_TRUE(two) << two.message();
  EXPECT_EQ(two->surface.cols(), 20);
  EXPECT_NEAR(enclosed_volume(*two), 2.0, 1e-9);

  // the first brick cut into 6 tetrahedra around its diagonal 0-6 (Kuhn); every other one is
  // listed in the mirrored turn
  const std::vector<int> b = bricks[0].nodes;
  const int paths[6][2] = {{1, 2}, {3, 2}, {3, 7}, {4, 7}, {4, 5}, {1, 5}};
  std::vector<FrdElement> tetrahedra;
  for (const auto& path : paths) tetrahedra.push_back({3, {b[0], b[path[0]], b[path[1]], b[6]}});
  Result<FemSolution> six = read_calculix_frd(write_temp("six_tetrahedra.frd", frd_text(nodes, tetrahedra, still)));
  ASSERT_TRUE(six) << six.message();
  EXPECT_EQ(six->surface.cols(), 12);
  EXPECT_NEAR(enclosed_volume(*six), 1.0, 1e-9);
}

TEST(CalculixResult, TheLastDisplacementBlockIsTheResult) {
  // a nonlinear step writes one DISP block per increment; the end of the step is the last one
  const std::string text = read_text(kOneBrick);
  const std::size_t first = text.find(" -4  DISP");
  const std::size_t end = text.find(" 9999");
  std::string doubled = text.substr(0, end) + text.substr(first, end - first);
  const std::string last = " -1         2-9.23074E-07-2.18623E-07-2.19837E-06";
  doubled.replace(doubled.rfind(last), last.size(), " -1         2 1.00000E-03 2.00000E-03-3.00000-100");
  Result<FemSolution> read = read_calculix_frd(write_temp("two_increments.frd", doubled + " 9999\n"));
  ASSERT_TRUE(read) << read.message();
  EXPECT_EQ(read->displacements(0, 1), 1e-3);
  EXPECT_EQ(read->displacements(2, 1), -3e-100);  // Fortran drops the E of a three-digit exponent
}

TEST(CalculixResult, BadFilesNameTheFileAndTheFault) {
  const std::string text = read_text(kOneBrick);
  const auto error_of = [](const std::string& name, const std::string& contents) {
    Result<FemSolution> read = read_calculix_frd(write_temp(name, contents));
    EXPECT_FALSE(read) << name;
    return read.message();
  };
  const auto edited = [&](const std::string& from, const std::string& to) {
    std::string copy = text;
    copy.replace(copy.find(from), from.size(), to);
    return copy;
  };
  const std::string missing = read_calculix_frd("/nonexistent/beam.frd").message();
  EXPECT_NE(missing.find("/nonexistent/beam.frd: cannot open"), std::string::npos) << missing;
  const std::string garbled = error_of("garbled.frd", edited("-9.23074E-07-2.18623E-07", "-9.23074E-07-2.1x623E-07"));
  EXPECT_NE(garbled.find("garbled.frd:34: '-2.1x623E-07' is not a finite number (node 2)"), std::string::npos)
      << garbled;
  const std::string nan = error_of("nan.frd", edited("-9.23074E-07-2.18623E-07", "-9.23074E-07         nan"));
  EXPECT_NE(nan.find("is not a finite number"), std::string::npos) << nan;
  const std::string no_displacement = error_of("no_disp.frd", text.substr(0, text.find("    1PSTEP")) + " 9999\n");
  EXPECT_NE(no_displacement.find("no displacements (DISP block); the deck needs '*NODE FILE'"), std::string::npos)
      << no_displacement;
  const std::string cut = error_of(
      "cut.frd", text.substr(0, text.find(" -1         5 0.00000E+00 0.00000E+00 0.00000E+00\n -1         6")));
  EXPECT_NE(cut.find("cut.frd:"), std::string::npos);
  EXPECT_NE(cut.find("ends inside a block"), std::string::npos) << cut;
  const std::string shell =
      error_of("shell.frd", edited(" -1         1    1    0    1", " -1         1    9    0    1"));
  EXPECT_NE(shell.find("element 1 has frd type 9; only solid elements"), std::string::npos) << shell;
  const std::string unknown_node =
      error_of("unknown_node.frd", edited("         7         8\n", "         7        80\n"));
  EXPECT_NE(unknown_node.find("element 1 uses node 80, which the node block does not define"), std::string::npos)
      << unknown_node;
  const std::string short_list = error_of("short_list.frd", edited("         7         8\n", "         7\n"));
  EXPECT_NE(short_list.find("element 1 of type 1 lists 7 nodes; expected 8"), std::string::npos) << short_list;
  const std::string not_frd = error_of("mesh.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_NE(not_frd.find("no node block (2C)"), std::string::npos) << not_frd;
  // a line with no end (a binary file, /dev/zero) is refused at a bound, not read whole
  const std::string endless = error_of("endless.frd", text.substr(0, 200) + std::string(100000, 'x') + "\n");
  EXPECT_NE(endless.find("endless.frd:"), std::string::npos) << endless;
  EXPECT_NE(endless.find("a line longer than 4096 characters"), std::string::npos) << endless;
  const std::string zeros = read_calculix_frd("/dev/zero").message();
  EXPECT_NE(zeros.find("/dev/zero:1: a line longer than 4096 characters"), std::string::npos) << zeros;
  // the last line may end without a line break (here the block's closing " -3": a character
  // lost from it would leave the file inside a block), and lines up to the bound are read
  const std::size_t last_close = text.rfind(" -3\n");
  ASSERT_NE(last_close, std::string::npos);
  const Result<FemSolution> no_last_break =
      read_calculix_frd(write_temp("no_last_break.frd", text.substr(0, last_close + 3)));
  EXPECT_TRUE(no_last_break) << no_last_break.message();
  const std::string longest_comment = "    1UUSER" + std::string(4096 - 10, ' ');
  ASSERT_EQ(longest_comment.size(), 4096u);
  EXPECT_TRUE(read_calculix_frd(write_temp("long_line.frd", longest_comment + "\n" + text)))
      << "a line of 4096 characters";
  const std::string too_long = error_of("too_long.frd", longest_comment + " \n" + text);
  EXPECT_NE(too_long.find("too_long.frd:1: a line longer than 4096 characters"), std::string::npos) << too_long;
  // a directory opens, and then cannot be read
  const std::string directory = read_calculix_frd(::testing::TempDir()).message();
  EXPECT_EQ(directory.find("longer than"), std::string::npos) << directory;
  EXPECT_NE(directory.find("cannot"), std::string::npos) << directory;
}

// The cantilever against a reference made from its own nodes, displaced 10% further.
ExperimentResult small_cantilever() {
  ExperimentSettings settings;
  settings.cells = {6, 2, 2};
  Result<ExperimentResult> result = run_experiment(Experiment::kCantilever, settings);
  EXPECT_TRUE(result) << result.message();
  return std::move(result).value();
}

FemSolution scaled_copy(const ExperimentResult& lattice, double factor) {
  FemSolution fem;
  fem.rest_positions = lattice.model.rest_positions;
  fem.displacements = factor * (lattice.state.positions - lattice.model.rest_positions);
  for (int n = 0; n < lattice.model.num_nodes(); ++n) fem.node_ids.push_back(n + 1);
  return fem;
}

TEST(FemComparison, AReferenceTenPercentFurtherGivesItsErrors) {
  const ExperimentResult lattice = small_cantilever();
  const FemComparison c = compare_cantilever_with_fem(lattice, scaled_copy(lattice, 1.1));
  EXPECT_EQ(c.matched_nodes, lattice.model.num_nodes());
  ASSERT_TRUE(c.tip_error);
  EXPECT_NEAR(*c.reference_tip_deflection, 1.1 * *lattice.tip_deflection, 1e-15);
  EXPECT_NEAR(*c.tip_error, 1 / 1.1 - 1, 1e-12);
  // |u - 1.1 u| / |1.1 tip| node by node
  const Eigen::VectorXd moved = (lattice.state.positions - lattice.model.rest_positions).colwise().norm();
  const double scale = 0.1 / (1.1 * std::abs(*lattice.tip_deflection));
  EXPECT_NEAR(*c.max_nodal_error, scale * moved.maxCoeff(), 1e-12);
  EXPECT_NEAR(*c.mean_nodal_error, scale * moved.mean(), 1e-12);
}

TEST(FemComparison, NodesAreMatchedByRestPositionOnly) {
  const ExperimentResult lattice = small_cantilever();
  FemSolution shifted = scaled_copy(lattice, 1.0);
  shifted.rest_positions.row(1).array() += 0.5 * lattice.settings.cell_size.y();  // between the lattice's nodes
  const FemComparison none = compare_cantilever_with_fem(lattice, shifted);
  EXPECT_EQ(none.matched_nodes, 0);
  EXPECT_FALSE(none.tip_error);

  // a reference without the tip's nodes still matches the others, but gives no figures
  FemSolution short_beam = scaled_copy(lattice, 1.0);
  const double tip_x = lattice.settings.cells.x() * lattice.settings.cell_size.x();
  int tip_nodes = 0;
  for (Eigen::Index n = 0; n < short_beam.rest_positions.cols(); ++n) {
    if (std::abs(short_beam.rest_positions(0, n) - tip_x) < 1e-9) {
      short_beam.rest_positions(0, n) += 0.3 * lattice.settings.cell_size.x();
      ++tip_nodes;
    }
  }
  const FemComparison partial = compare_cantilever_with_fem(lattice, short_beam);
  EXPECT_EQ(partial.matched_nodes, lattice.model.num_nodes() - tip_nodes);
  EXPECT_FALSE(partial.tip_error);
  EXPECT_FALSE(partial.max_nodal_error);
}

}  // namespace
}  // namespace cubespring
