// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The cubespring tool as a user scripts it: JSON keys and values, and one-line errors for bad input.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/tool_run.h"
#include "json_output.h"

namespace {

using cubespring::test::run_tool;
using cubespring::test::ToolRun;

nlohmann::json run_json(const std::string& arguments) {
  const ToolRun run = run_tool(arguments + " --json", false);
  EXPECT_EQ(run.exit_code, 0) << run.out;
  return nlohmann::json::parse(run.out);
}

TEST(Cli, ElongationJsonCarriesTheContractKeys) {
  const nlohmann::json j = run_json("measure elongation --young 2e5 --poisson 0.45");
  for (const char* key : {"inputs", "measured", "expected", "error"}) EXPECT_TRUE(j.contains(key)) << key;
  for (const char* key :
       {"young_modulus", "poisson_ratio", "density", "cells", "cell_size", "strain", "gravity", "model"}) {
    EXPECT_TRUE(j["inputs"].contains(key)) << key;
  }
  EXPECT_EQ(j["inputs"]["model"], "baudet2007");
  EXPECT_DOUBLE_EQ(j["inputs"]["young_modulus"].get<double>(), 2e5);
  EXPECT_NEAR(j["measured"]["young_modulus"].get<double>() / 2e5, 1.0, 1e-3);
  EXPECT_NEAR(j["measured"]["poisson_ratio"].get<double>(), 0.45, 1e-3);
  EXPECT_LT(std::abs(j["error"]["young_modulus"].get<double>()), 1e-3);
}

TEST(Cli, InflationAndShearMeasureTheirModuli) {
  const nlohmann::json b = run_json("measure inflation --poisson 0.49 --cells 2,2,2");
  EXPECT_NEAR(b["measured"]["bulk_modulus"].get<double>() / b["expected"]["bulk_modulus"].get<double>(), 1.0, 1e-3);
  const nlohmann::json g = run_json("measure shear");
  EXPECT_EQ(g["inputs"]["control"], "displacement");
  EXPECT_NEAR(g["error"]["shear_modulus"].get<double>(), 0.0, 1e-3);
  const nlohmann::json f = run_json("measure shear --control force");
  EXPECT_EQ(f["inputs"]["control"], "force");
  EXPECT_NEAR(f["measured"]["shear_modulus"].get<double>() / f["expected"]["shear_modulus"].get<double>(),
              (1 + 4 * 0.3) / (2 + 4 * 0.3), 1e-3);
}

TEST(Cli, CantileverReportsTipAndEveryNode) {
  const nlohmann::json j = run_json("measure cantilever --cells 8,2,2 --cell-size 0.02");
  const double tip = j["tip_deflection"].get<double>();
  EXPECT_LT(tip, 0.0);
  ASSERT_EQ(j["nodes"].size(), 9u * 3 * 3);
  double sum = 0;
  int count = 0;
  for (const auto& node : j["nodes"]) {
    ASSERT_EQ(node["rest"].size(), 3u);
    ASSERT_EQ(node["displacement"].size(), 3u);
    if (std::abs(node["rest"][0].get<double>() - 0.16) < 1e-12) {
      sum += node["displacement"][2].get<double>();
      ++count;
    }
  }
  EXPECT_EQ(count, 9);
  EXPECT_NEAR(sum / count, tip, 1e-15);
  EXPECT_LT(j["expected"]["timoshenko"].get<double>(), j["expected"]["euler_bernoulli"].get<double>());
}

TEST(Cli, ExactBendingModelIsSelectableAndNamed) {
  const nlohmann::json j = run_json("measure elongation --model exact-bending --poisson 0.45");
  EXPECT_EQ(j["inputs"]["model"], "exact-bending");
  EXPECT_DOUBLE_EQ(j["inputs"]["edge_fraction"].get<double>(), 0.07);
  EXPECT_NEAR(j["error"]["young_modulus"].get<double>(), 0.0, 1e-3);
  const nlohmann::json beam = run_json("measure cantilever --model exact-bending --edge-fraction 0.08333333333333333");
  const nlohmann::json paper = run_json("measure cantilever");
  // exact cell bending sags more than the paper's stiff edges
  EXPECT_LT(beam["tip_deflection"].get<double>(), 1.05 * paper["tip_deflection"].get<double>());
  const ToolRun bad = run_tool("measure cantilever --model exact-bending --cell-size 0.01,0.01,0.012");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.out.find("cubic cells only"), std::string::npos) << bad.out;
}

TEST(Cli, LawIsSelectableAndNamed) {
  EXPECT_EQ(run_json("measure elongation")["inputs"]["law"], "springs");
  const nlohmann::json j =
      run_json("measure elongation --law neo-hookean --model exact-bending --poisson 0.49 --cells 4,4,4");
  EXPECT_EQ(j["inputs"]["law"], "neo-hookean");
  EXPECT_NEAR(j["error"]["young_modulus"].get<double>(), 0.0, 1e-3);
  EXPECT_NEAR(j["error"]["poisson_ratio"].get<double>(), 0.0, 1e-3);
  const ToolRun bad = run_tool("measure elongation --law mooney");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.out.find("--law"), std::string::npos) << bad.out;
}

// A soft block under its own weight: the sag and volume change in the JSON (the CalculiX
// comparison is tests/validation/test_self_weight_fem.cpp); the default block is a 12 cm cube.
TEST(Cli, SelfWeightReportsTheSagAndTheVolumeChange) {
  const nlohmann::json j = run_json(
      "measure self-weight --young 5000 --poisson 0.45 --density 1060 --law neo-hookean --model exact-bending "
      "--cells 4,4,4 --cell-size 0.03");
  EXPECT_EQ(j["experiment"], "self-weight");
  EXPECT_EQ(j["inputs"]["law"], "neo-hookean");
  EXPECT_EQ(j["inputs"]["cells"], nlohmann::json::array({4, 4, 4}));
  // the 12 cm cube sags about 12 mm (CalculiX: 12.2 mm) and loses about 1.5% of its volume
  EXPECT_LT(j["measured"]["top_centre_uz"].get<double>(), -0.010);
  EXPECT_GT(j["measured"]["top_centre_uz"].get<double>(), -0.014);
  EXPECT_LT(j["measured"]["volume_change"].get<double>(), -0.01);
  EXPECT_GT(j["measured"]["volume_change"].get<double>(), -0.02);
  EXPECT_GT(j["measured"]["least_cell_volume_ratio"].get<double>(), 0.5);
  EXPECT_EQ(j["inputs"]["support"], "bonded");
  // on a frictionless floor the base spreads: it sags further (CalculiX: 13.9 mm)
  const nlohmann::json floor = run_json(
      "measure self-weight --young 5000 --poisson 0.45 --density 1060 --law neo-hookean --model exact-bending "
      "--cells 4,4,4 --cell-size 0.03 --support floor");
  EXPECT_EQ(floor["inputs"]["support"], "floor");
  EXPECT_LT(floor["measured"]["top_centre_uz"].get<double>(), j["measured"]["top_centre_uz"].get<double>());
  const ToolRun table = run_tool("measure self-weight --cells 2,2,2");
  EXPECT_EQ(table.exit_code, 0) << table.out;
  EXPECT_NE(table.out.find("volume change"), std::string::npos) << table.out;
  const ToolRun unloaded = run_tool("measure self-weight --cells 2,2,2 --gravity 0");
  EXPECT_NE(unloaded.exit_code, 0);
  EXPECT_NE(unloaded.out.find("--gravity"), std::string::npos) << unloaded.out;
}

// Compression between bonded plates: the plate's force, the bulge and the volume in the JSON (the
// CalculiX comparison is tests/validation/test_bonded_compression_fem.cpp).
TEST(Cli, BondedCompressionReportsThePlateForceTheBulgeAndTheVolume) {
  const nlohmann::json j = run_json(
      "measure bonded-compression --young 15300 --poisson 0.49 --law neo-hookean --model exact-bending "
      "--cells 4,4,4 --cell-size 0.02 --strain -0.1 --points 2");
  EXPECT_EQ(j["experiment"], "bonded-compression");
  ASSERT_EQ(j["curve"].size(), 2u);
  EXPECT_DOUBLE_EQ(j["curve"][1]["strain"].get<double>(), -0.1);
  const double force = j["measured"]["platen_force"].get<double>();
  // pressed, the plate pushes down: more than E A strain (the bonded faces cannot spread)
  EXPECT_LT(force, -15300 * 0.08 * 0.08 * 0.1);
  EXPECT_NEAR(j["measured"]["stress"].get<double>(), force / (0.08 * 0.08), 1e-9 * std::abs(force));
  EXPECT_GT(j["measured"]["bulge"].get<double>(), 0.0);                     // the sides bulge out
  EXPECT_LT(std::abs(j["measured"]["volume_change"].get<double>()), 0.01);  // nearly incompressible
  EXPECT_GT(j["measured"]["least_cell_volume_ratio"].get<double>(), 0.9);
  const ToolRun table = run_tool("measure bonded-compression --cells 2,2,2 --points 1");
  EXPECT_EQ(table.exit_code, 0) << table.out;
  EXPECT_NE(table.out.find("platen force"), std::string::npos) << table.out;
  const ToolRun unloaded = run_tool("measure bonded-compression --cells 2,2,2 --strain 0");
  EXPECT_NE(unloaded.exit_code, 0);
  EXPECT_NE(unloaded.out.find("--strain"), std::string::npos) << unloaded.out;
}

// Numbers whose results would not be finite are refused by their flag, with the range taken,
// never printed as inf or nan with exit 0 (issue 30's cases); an empty number is not 0.
TEST(Cli, MeasureRefusesNumbersWhoseResultsWouldNotBeFinite) {
  struct Case {
    const char* arguments;
    const char* flag;
    const char* says;
  };
  for (const Case& c : {Case{"measure elongation --young 1e308", "--young", "1e+13"},
                        Case{"measure elongation --young 1e-300", "--young", "0.001"},
                        Case{"measure elongation --strain 1e-300", "--strain", "1e-09"},
                        Case{"measure uniaxial --strain -1e-300 --law neo-hookean", "--strain", "1e-09"},
                        Case{"measure cantilever --density 1e308", "--density", "1e+06"},
                        Case{"measure cantilever --gravity 1e308", "--gravity", "1e+06"},
                        Case{"measure elongation --poisson ''", "--poisson", "not a number"},
                        Case{"measure elongation --young ''", "--young", "not a number"}}) {
    const ToolRun run = run_tool(c.arguments);
    EXPECT_NE(run.exit_code, 0) << c.arguments << ": " << run.out;
    EXPECT_NE(run.out.find(c.flag), std::string::npos) << c.arguments << ": " << run.out;
    EXPECT_NE(run.out.find(c.says), std::string::npos) << c.arguments << ": " << run.out;
    EXPECT_EQ(run.out.find("nan"), std::string::npos) << c.arguments << ": " << run.out;
    EXPECT_LT(run.out.size(), 300u) << c.arguments << ": a line or two";
  }
}

// A block too large for the static solver is refused before anything is built, with the
// estimate and the limit, in a line (100^3 took minutes with no word, then all the memory); a
// block whose factorisations take a while is announced on stderr before the run starts.
TEST(Cli, MeasureRefusesABlockTooLargeForItsMemoryAndAnnouncesALongOne) {
  ToolRun run = run_tool("measure elongation --cells 100,100,100");
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find("--cells: cells = 100,100,100: the block and its static solver's factorisation take about"),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("--max-memory"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("measure: 100 x 100 x 100"), std::string::npos) << "refused, not announced: " << run.out;
  EXPECT_LT(run.out.size(), 300u) << run.out;
  // the limit given: a 34^3 block's estimate (about 1.4 GB) against 0.5 GB
  run = run_tool("measure elongation --cells 34,34,34 --max-memory 500000000");
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find("more than the memory limit of 0.5 GB;"), std::string::npos) << run.out;
  run = run_tool("measure elongation --max-memory -1");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("--max-memory: '-1' is not a whole number of bytes"), std::string::npos) << run.out;
  // a 34^3 block (about 100 s a factorisation) is announced before it starts: stopped after 4 s
  run = run_tool("measure elongation --cells 34,34,34 2>&1 & sleep 4; kill $! 2>/dev/null; wait");
  EXPECT_NE(run.out.find("measure: 34 x 34 x 34 cells: each factorisation of the stiffness (one a Newton iteration) "
                         "takes about 1.4 GB"),
            std::string::npos)
      << run.out;
  // a small block runs as before, without a word on stderr (run_tool reads both streams)
  run = run_tool("measure elongation --cells 4,4,4 --max-memory 500000000");
  EXPECT_EQ(run.exit_code, 0) << run.out;
  EXPECT_EQ(run.out.find("measure: "), std::string::npos) << run.out;
}

// voxelize's numbers: ranges stated plainly (not DBL_MAX in 309 digits), a scale that overflows
// the mesh's volume named (it said "needs about -nan MB"), a negative byte count refused (it
// wrapped to 2^64 - 1).
TEST(Cli, VoxelizeRefusesNumbersOutOfRangeByName) {
  const std::string mesh = std::string(CUBESPRING_DATA_DIR) + "/liver.obj";
  ToolRun run = run_tool("voxelize " + mesh + " --cells-across 0");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("--cells-across: Value 0 not in range 1 to 100000"), std::string::npos) << run.out;
  EXPECT_LT(run.out.size(), 200u) << run.out;
  run = run_tool("voxelize " + mesh + " --scale 1e300");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("out of the range of double"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("nan"), std::string::npos) << run.out;
  run = run_tool("voxelize " + mesh + " --max-memory -1");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("--max-memory: '-1' is not a whole number of bytes"), std::string::npos) << run.out;
}

// An argument of kilobytes, or with a line break, or many arguments, were echoed whole into
// the error (found by tests/fuzz/fuzz_cli.cpp): the error stays one short line that names the
// flag, the argument cut and escaped.
TEST(Cli, AnArgumentOfKilobytesOrWithALineBreakStaysOneShortLine) {
  const std::string nines(700, '9');
  std::string counts;
  for (int i = 0; i < 400; ++i) counts += "1,";
  const std::string words(900, 'x');
  std::string many;  // CLI11 lists every argument it did not expect
  for (int i = 0; i < 40; ++i) many += " unexpected_" + std::to_string(i) + "_argument";
  const std::pair<std::string, std::string> cases[] = {
      {"measure elongation " + words, "error: The following argument was not expected: xxxx"},
      {"measure elongation" + many, "error: The following arguments were not expected: unexpected_"},
      {"measure cantilever --reference " + words + ".frd", "error: --reference: xxxx"},
      {"measure elongation --cells " + counts + "1", "error: --cells 1,1,1,"},
      {"measure elongation --young " + nines, "error: --young: '9999"},
      {"measure elongation --young '1\n2'", "error: --young: '1\\n2' is not a number"},  // a real line break
      {"voxelize any.obj --cell-size " + counts, "error: --cell-size 1,1,1,"},
  };
  for (const auto& [arguments, expected] : cases) {
    const ToolRun run = run_tool(arguments);
    SCOPED_TRACE(arguments.substr(0, 60));
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.out.find(expected), 0u) << run.out;
    EXPECT_LT(run.out.size(), 320u) << run.out;
    EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1) << run.out;
  }
}

// The neo-Hookean law's default cells are exact-bending, as in scenes and the plugin; the paper's
// are there when asked for.
TEST(Cli, TheNeoHookeanLawTakesExactBendingCellsUnlessToldOtherwise) {
  EXPECT_EQ(run_json("measure hydrostatic --law neo-hookean --points 1")["inputs"]["model"], "exact-bending");
  EXPECT_EQ(run_json("measure elongation")["inputs"]["model"], "baudet2007");
  EXPECT_EQ(run_json("measure hydrostatic --law neo-hookean --model baudet2007 --points 1")["inputs"]["model"],
            "baudet2007");
}

// The reports' last guard: the first number that is not finite, by its key path.
TEST(Cli, ReportsFindTheirFirstNumberThatIsNotFinite) {
  nlohmann::json report = {{"measured", {{"a", 1.0}, {"b", 2}}}, {"curve", {{{"stress", 1.0}}, {{"stress", 3.0}}}}};
  EXPECT_FALSE(cubespring::app::first_non_finite(report).has_value());
  report["curve"][1]["stress"] = std::numeric_limits<double>::quiet_NaN();
  std::optional<cubespring::app::NonFinite> found = cubespring::app::first_non_finite(report);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->path, "curve[1].stress");
  report["measured"]["a"] = -std::numeric_limits<double>::infinity();
  found = cubespring::app::first_non_finite(report);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->path, "curve[1].stress");  // objects' keys in order: "curve" before "measured"
  report["curve"][1]["stress"] = 0.0;
  EXPECT_EQ(cubespring::app::first_non_finite(report)->path, "measured.a");
  EXPECT_EQ(cubespring::app::first_non_finite(report)->value, -std::numeric_limits<double>::infinity());
}

// Width and height from a PNG's header (the IHDR chunk follows the 8-byte signature).
std::pair<int, int> png_size(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return {0, 0};
  std::array<unsigned char, 24> head{};
  const std::size_t read = std::fread(head.data(), 1, head.size(), file);
  std::fclose(file);
  if (read != head.size() || head[1] != 'P' || head[2] != 'N' || head[3] != 'G') return {0, 0};
  const auto big_endian = [&](int at) {
    return (head[at] << 24) | (head[at + 1] << 16) | (head[at + 2] << 8) | head[at + 3];
  };
  return {big_endian(16), big_endian(20)};
}

TEST(Cli, CantileverDrawsItsPictureAndComparesWithAReference) {
  // one_brick.frd is a CalculiX result for the beam's first cell only: its 8 nodes match, the tip
  // does not, so there are no error figures
  const std::string png = ::testing::TempDir() + "cli_cantilever.png";
  std::remove(png.c_str());
  const nlohmann::json j =
      run_json("measure cantilever --cells 8,2,2 --png " + png +
               " --width 320 --height 180 --reference " CUBESPRING_TEST_DATA_DIR "/calculix/one_brick.frd");
  EXPECT_EQ(j["png"], png);
  EXPECT_EQ(png_size(png), std::make_pair(320, 180));
  const nlohmann::json& reference = j["reference"];
  EXPECT_EQ(reference["lattice_nodes"], 9 * 3 * 3);
  EXPECT_EQ(reference["matched_nodes"], 8);
  for (const char* key : {"tip_deflection", "tip_error", "mean_nodal_error", "max_nodal_error"}) {
    EXPECT_TRUE(reference.contains(key) && reference[key].is_null()) << key;
  }
  const ToolRun table =
      run_tool("measure cantilever --cells 8,2,2 --reference " CUBESPRING_TEST_DATA_DIR "/calculix/one_brick.frd");
  EXPECT_EQ(table.exit_code, 0);
  EXPECT_NE(table.out.find("8 of 81 lattice nodes matched"), std::string::npos) << table.out;
}

TEST(Cli, TableWithoutJson) {
  const ToolRun run = run_tool("measure elongation");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("young_modulus"), std::string::npos) << run.out;
}

// The demo's organ: two parts, the tumour inside the liver.
TEST(Cli, VoxelizeReportsPartsVolumesCountsAndProblems) {
  const nlohmann::json j = run_json("voxelize " CUBESPRING_DATA_DIR "/liver.obj --cells-across 40");
  ASSERT_EQ(j["parts"].size(), 2u);
  EXPECT_EQ(j["parts"][0]["name"], "liver");
  EXPECT_EQ(j["parts"][0]["material"], "liver_tissue");
  EXPECT_EQ(j["parts"][1]["name"], "tumour");
  EXPECT_GT(j["parts"][1]["cells"].get<int>(), 0);
  EXPECT_LT(std::abs(j["relative_volume_difference"].get<double>()), 0.03);
  // the tumour lies inside the liver: the mesh volume is the liver's alone
  EXPECT_DOUBLE_EQ(j["mesh_volume"].get<double>(), j["parts"][0]["mesh_volume"].get<double>());
  EXPECT_EQ(j["cells"].get<int>(), j["parts"][0]["cells"].get<int>() + j["parts"][1]["cells"].get<int>());
  EXPECT_GT(j["nodes"].get<int>(), j["cells"].get<int>());
  EXPECT_GT(j["springs"].get<int>(), 4 * j["cells"].get<int>());
  EXPECT_GT(j["memory_estimate_bytes"].get<double>(), 0.0);
  for (const char* key : {"open_edges", "non_manifold_edges", "inconsistent_orientation", "degenerate_triangles",
                          "duplicate_triangles", "edge_only_contacts", "corner_only_contacts", "islands"}) {
    EXPECT_TRUE(j["problems"].contains(key)) << key;
  }
  EXPECT_EQ(j["problems"]["open_edges"], 0);
  const double h = j["cell_size"][0].get<double>();
  EXPECT_NEAR(h, 0.22 / 40, 1e-6);
}

// A part name in Latin-1 ("Leber_gr\xfcn", as older tools write OBJ files) is not UTF-8: the JSON
// still comes out whole, the byte replaced by U+FFFD, instead of the tool aborting halfway.
TEST(Cli, VoxelizeJsonTakesANameThatIsNotUtf8) {
  // a name of its own: another build tree's ctest may run this test at the same time
  const std::filesystem::path obj =
      std::filesystem::temp_directory_path() / ("cubespring_latin1_cube_" + std::to_string(::getpid()) + ".obj");
  {
    std::ofstream out(obj, std::ios::binary);
    out << "o Leber_gr\xfcn\n";
    for (const char* v :
         {"0 0 0", "0.1 0 0", "0.1 0.1 0", "0 0.1 0", "0 0 0.1", "0.1 0 0.1", "0.1 0.1 0.1", "0 0.1 0.1"}) {
      out << "v " << v << "\n";
    }
    out << "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";  // outward
  }
  const nlohmann::json j = run_json("voxelize " + obj.string() + " --cells-across 4");
  std::filesystem::remove(obj);
  ASSERT_EQ(j["parts"].size(), 1u);
  EXPECT_EQ(j["parts"][0]["name"], "Leber_gr\xef\xbf\xbdn");
}

TEST(Cli, VoxelizeTableNamesTheParts) {
  const ToolRun run = run_tool("voxelize " CUBESPRING_DATA_DIR "/liver.obj --cell-size 0.01");
  EXPECT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("tumour_tissue"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("voxel volume"), std::string::npos) << run.out;
}

// `cubespring bench...` runs cubespring-bench from beside the cubespring program; a cubespring
// copied away from it says what is missing, in one line, and exits 1.
TEST(Cli, ABenchmarkWithoutItsProgramSaysWhatIsMissing) {
  namespace fs = std::filesystem;
  const fs::path alone = fs::path(::testing::TempDir()) / "cubespring_alone";
  fs::create_directories(alone);
  fs::copy_file(CUBESPRING_CLI_PATH, alone / "cubespring", fs::copy_options::overwrite_existing);
  const std::string command = (alone / "cubespring").string() + " bench-layout --json 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) out += buffer.data();
  const int status = pclose(pipe);
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 1) << out;
  EXPECT_EQ(out.find("error: `cubespring bench-layout` runs the benchmarks' own program, " +
                     (alone / "cubespring-bench").string() + ", which is not there"),
            0u)
      << out;
  EXPECT_NE(out.find("CUBESPRING_BUILD_BENCHMARKS=OFF"), std::string::npos) << out;
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
  fs::remove_all(alone);
}

#ifdef CUBESPRING_HAS_BENCHMARKS
// A short core bench run: one row per body with the documented JSON keys, the bodies' sizes counted
// by hand (a 2x2x2 box: 27 nodes, 54 edges + 32 inner diagonals), every timed column a positive time
// (the 2-thread ceiling from the 1-thread step and two bodies at once); the floor with implicit
// connectivity for boxes only (it must visit the model's spring count).
TEST(Cli, BenchRowsCountTheBodyAndTimeEveryColumn) {
  const nlohmann::json rows =
      run_json("bench --sizes '2,2,2;3,1,1' --sphere 4 --min-seconds 0.01 --implicit-max-cells 100 --json");
  ASSERT_TRUE(rows.is_array());
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[2]["body"], "sphere 4");
  EXPECT_TRUE(rows[2]["grid_bare_spring_pass_ms"].is_null()) << rows[2].dump();
  for (int box = 0; box < 2; ++box)
    EXPECT_GT(rows[box]["grid_bare_spring_pass_ms"].get<double>(), 0.0) << rows[box].dump();
  const nlohmann::json& box = rows[0];
  EXPECT_EQ(box["body"], "2x2x2");
  EXPECT_EQ(box["cells"], 8);
  EXPECT_EQ(box["nodes"], 27);
  EXPECT_EQ(box["springs"], 86);
  EXPECT_EQ(rows[1]["springs"], 3 * 4 + 4 * 2 + 4 * 2 + 4 * 3) << "3x1x1: 12 x-edges, 8 y-, 8 z-edges, 12 diagonals";
  for (const nlohmann::json& row : rows) {
    EXPECT_GT(row["bare_spring_pass_ms"].get<double>(), 0.0) << row.dump();
    EXPECT_GT(row["symplectic_euler_ms"]["1"].get<double>(), 0.0) << row.dump();
    EXPECT_GT(row["symplectic_euler_ms"]["2"].get<double>(), 0.0) << row.dump();
    EXPECT_GT(row["velocity_verlet_ms"]["1"].get<double>(), 0.0) << row.dump();
    EXPECT_GT(row["velocity_verlet_ms"]["2"].get<double>(), 0.0) << row.dump();
    EXPECT_GT(row["exact_bending_symplectic_euler_ms"]["1"].get<double>(), 0.0) << row.dump();
    const double two_bodies = row["two_bodies_at_once_ms"].get<double>();
    EXPECT_GT(two_bodies, 0.0) << row.dump();
    EXPECT_NEAR(row["two_thread_ceiling"].get<double>(),
                2.0 * row["symplectic_euler_ms"]["1"].get<double>() / two_bodies, 1e-12)
        << row.dump();
    EXPECT_GT(row["implicit_euler_ms"].get<double>(), 0.0) << row.dump();
    EXPECT_EQ(row["implicit_euler_threads_ms"]["1"], row["implicit_euler_ms"]) << row.dump();
    EXPECT_GT(row["implicit_euler_threads_ms"]["2"].get<double>(), 0.0) << row.dump();
    EXPECT_GT(row["implicit_cg_iterations"].get<int>(), 0) << row.dump();
  }
}

// A short bench-layout run: each fill in both models, one material and with an inclusion, on the
// same hollow ball (the same cell count), near the fill asked; the layout the default fill picks is
// the grid exactly from kDefaultMinGridFill (0.45) on (a ball of 20 across fills 0.450: 3600 of
// 8000 cells); every time positive. A fill that is not a fraction is refused by name.
TEST(Cli, BenchLayoutTimesBothLayoutsByFill) {
  const nlohmann::json rows = run_json("bench-layout --cells-across 20 --fills 0.3,0.45 --min-seconds 0.01");
  ASSERT_TRUE(rows.is_array());
  ASSERT_EQ(rows.size(), 8u);
  EXPECT_EQ(rows[4]["cells"], 3600);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const nlohmann::json& row = rows[i];
    const double asked = i < 4 ? 0.3 : 0.45;
    EXPECT_NEAR(row["fill"].get<double>(), asked, 0.02) << row.dump();
    EXPECT_EQ(row["default_layout"], i < 4 ? "lists" : "grid") << row.dump();
    EXPECT_EQ(row["cells"], rows[i < 4 ? 0 : 4]["cells"]) << row.dump();
    EXPECT_EQ(row["model"], i % 4 < 2 ? "baudet2007" : "exact-bending") << row.dump();
    EXPECT_EQ(row["materials"], i % 2 == 0 ? "one" : "inclusion") << row.dump();
    EXPECT_EQ(row["default_layout"], row["fill"].get<double>() >= 0.45 ? "grid" : "lists") << row.dump();
    for (const char* layout : {"lists_ms", "grid_ms"}) {
      for (const char* threads : {"1", "2"}) EXPECT_GT(row[layout][threads].get<double>(), 0.0) << row.dump();
    }
  }
  const ToolRun bad = run_tool("bench-layout --fills 0.3,0.8");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.out.find("--fills: '0.8' is not a fraction in (0, 0.52]"), std::string::npos) << bad.out;
}

#ifdef CUBESPRING_HAS_BULLET
// A short bench-bullet run: every engine's row, the explicit cubespring row once per thread count
// with the same tip to the bit (threads do not change results), and its JSON keys.
TEST(Cli, BenchBulletRowsCoverEveryEngineAndThreadCount) {
  const nlohmann::json rows = run_json(
      "bench-bullet --sizes 8,2,2 --seconds 0.05 --iterations 1 --models baudet2007 --threads 1,2 --max-case-seconds "
      "20");
  ASSERT_TRUE(rows.is_array());
  std::map<std::string, int> engines;
  std::map<int, double> explicit_tip;
  for (const nlohmann::json& row : rows) {
    for (const char* key : {"size", "engine", "case", "wall_s_per_sim_s", "cpu_s_per_sim_s", "tip_deflection_m",
                            "fe_reference_m", "error_vs_fe", "threads", "status"}) {
      EXPECT_TRUE(row.contains(key)) << key << " missing in " << row.dump();
    }
    ++engines[row["engine"].get<std::string>()];
    EXPECT_GT(row["wall_s_per_sim_s"].get<double>(), 0.0) << row.dump();
    if (row["engine"] == "cubespring explicit") {
      explicit_tip[row["threads"].get<int>()] = row["tip_deflection_m"].get<double>();
    }
  }
  EXPECT_EQ(engines["cubespring explicit"], 2);
  EXPECT_EQ(engines["cubespring implicit"], 1);
  EXPECT_EQ(engines["btSoftBody"], 1);
  EXPECT_EQ(engines["Bullet deformable FEM"], 1);
  ASSERT_EQ(explicit_tip.size(), 2u);
  EXPECT_LT(explicit_tip[1], 0.0) << "the beam sags under gravity";
  EXPECT_EQ(explicit_tip[1], explicit_tip[2]);
}
#endif

#ifdef CUBESPRING_HAS_BULLET_PLUGIN
// A short bench-contact run: a 5 mm probe pressed and dragged over the block of 1 cm cells at
// 10 cm/s, and a 20 g box dropped on it. The surface stays out of the probe within the contact
// issue's 0.5 mm, its force never halves while pressing, and the box rests carried by the tissue.
TEST(Cli, BenchContactProbesAndDropsWithinTheContactTargets) {
  const nlohmann::json out =
      run_json("bench-contact --cells-across 10 --radii 0.0025 --speeds 0.1 --steps 0.0166667 --drops 0.02");
  ASSERT_EQ(out["probes"].size(), 1u) << out.dump();
  const nlohmann::json& probe = out["probes"][0];
  EXPECT_EQ(probe["failure"], "") << probe.dump();
  EXPECT_LE(probe["deepest_m"].get<double>(), probe["allowed_m"].get<double>()) << probe.dump();
  EXPECT_EQ(probe["allowed_m"].get<double>(), 0.5e-3);
  EXPECT_EQ(probe["force_drops"].get<int>(), 0) << probe.dump();
  EXPECT_GT(probe["drag_force_N"].get<double>(), 0.05) << probe.dump();
  EXPECT_GT(probe["wall_per_simulated"].get<double>(), 0.0);
  ASSERT_EQ(out["drops"].size(), 1u) << out.dump();
  const nlohmann::json& drop = out["drops"][0];
  EXPECT_EQ(drop["failure"], "") << drop.dump();
  EXPECT_LT(drop["speed_m_per_s"].get<double>(), 1e-3) << drop.dump();
  EXPECT_NEAR(drop["carried_over_weight"].get<double>(), 1.0, 0.02) << drop.dump();
  EXPECT_GT(drop["sunk_m"].get<double>(), 0.0) << drop.dump();
}
#endif
#endif  // CUBESPRING_HAS_BENCHMARKS

struct BadArgument {
  const char* arguments;
  const char* named;  // what the one-line error must name
};

class CliRejects : public ::testing::TestWithParam<BadArgument> {};

TEST_P(CliRejects, WithOneLineNamingTheArgument) {
  const ToolRun run = run_tool(GetParam().arguments);
  EXPECT_NE(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find(GetParam().named), std::string::npos) << run.out;
  EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1) << run.out;
}

INSTANTIATE_TEST_SUITE_P(
    BadArguments, CliRejects,
    ::testing::Values(
        BadArgument{"measure twist", "twist"}, BadArgument{"measure elongation --poisson 0.5", "--poisson"},
        BadArgument{"measure elongation --young 0", "--young"},
        BadArgument{"measure elongation --cells 0,1,1", "--cells"},
        // 1e15 cells: more than int indices address; 1.3e8: about 250 GB once built
        BadArgument{"measure elongation --cells 100000,100000,100000", "--cells"},
        BadArgument{"measure elongation --cells 511,512,512", "memory limit"},
        BadArgument{"measure elongation --cell-size 1e-120", "--cell-size"},
        BadArgument{"measure cantilever --gravity 0", "--gravity"},
        BadArgument{"measure elongation --yung 1e6", "--yung"},
        BadArgument{"measure elongation --cell-size -0.01", "--cell-size"},
        BadArgument{"measure cantilever --cells 16,4", "--cells"},
        BadArgument{"measure shear --control torque", "--control"},
        BadArgument{"measure elongation --young abc", "--young"},
        BadArgument{"measure elongation --model tetra", "--model"},
        BadArgument{"measure elongation --model exact-bending --edge-fraction 0", "--edge-fraction"},
        BadArgument{"measure elongation --png beam.png", "--png"},
        BadArgument{"measure cantilever --reference /nonexistent/beam.frd", "/nonexistent/beam.frd"},
        BadArgument{"measure cantilever --reference " CUBESPRING_DATA_DIR "/liver.obj", "no node block"},
        BadArgument{"measure cantilever --png /nonexistent/dir/beam.png", "/nonexistent/dir/beam.png"},
        BadArgument{"measure cantilever --png beam.png --width 0", "--width"},
        BadArgument{"measure cantilever --png beam.png --magnify nan", "--magnify"},
        BadArgument{"bench --min-seconds 0", "--min-seconds"}, BadArgument{"bench --min-seconds nan", "--min-seconds"},
        BadArgument{"bench-layout --min-seconds inf", "--min-seconds"},
        BadArgument{"voxelize /nonexistent/organ.obj", "/nonexistent/organ.obj"},
        BadArgument{"voxelize " CUBESPRING_DATA_DIR "/liver.obj --cell-size 0", "--cell-size"},
        BadArgument{"voxelize " CUBESPRING_DATA_DIR "/liver.obj --cell-size 0.01 --cells-across 9", "--cells-across"},
        BadArgument{"voxelize " CUBESPRING_DATA_DIR "/liver.obj --scale -2", "-2"},
        BadArgument{"voxelize " CUBESPRING_DATA_DIR "/liver.obj --cell-size 0.0001 --max-memory 1000000",
                    "memory limit"},
        BadArgument{"voxelize " CUBESPRING_DATA_DIR "/liver.mtl", "liver.mtl"},
        BadArgument{"voxelize " CUBESPRING_DATA_DIR "/liver.obj --rule fraction --min-fraction 2", "--min-fraction"},
        BadArgument{"voxelize " CUBESPRING_DATA_DIR "/liver.obj --rule fraction --samples 9", "--samples"},
        BadArgument{"measure elongation --cells 200000,1,1", "from 1 to 100000"}));

#ifdef CUBESPRING_HAS_BULLET_PLUGIN
INSTANTIATE_TEST_SUITE_P(BenchContactBadArguments, CliRejects,
                         ::testing::Values(BadArgument{"bench-contact --radii 0.001,0", "--radii"},
                                           BadArgument{"bench-contact --cells-across 2.5", "--cells-across"},
                                           BadArgument{"bench-contact --mesh /nonexistent/organ.obj --radii 0.001 "
                                                       "--speeds 0.1 --steps 0.01 --cells-across 4 --drops 0.01",
                                                       "/nonexistent/organ.obj"}));
#endif

}  // namespace
