// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// CalculiX's .frd result format: CalculiX GraphiX manual, section "Result Format". Each line
// starts with a key; " -1" lines carry a node or element number right-justified in a fixed field
// followed by values 12 characters wide (E12.5, so a minus sign may touch the previous value).
#include "cubespring/validation/calculix_result.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include <Eigen/Geometry>

namespace cubespring {

namespace {

constexpr int kValueWidth = 12;

// An .frd line is at most a few hundred characters; a longer one is not such a file, and reading
// it whole would grow without end (/dev/zero, a binary file with no line break).
constexpr std::streamsize kMaxLineLength = 4096;

struct SolidType {
  int node_count;
  std::vector<std::vector<int>> faces;  // corner positions within the element's node list
};

// Corners come first in every frd solid: bricks 0-3 below 4-7, wedges 0-2 below 3-5.
const std::map<int, SolidType>& solid_types() {
  static const std::vector<std::vector<int>> brick{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                   {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  static const std::vector<std::vector<int>> wedge{{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
  static const std::vector<std::vector<int>> tetrahedron{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  static const std::map<int, SolidType> types{{1, {8, brick}},  {2, {6, wedge}},  {3, {4, tetrahedron}},
                                              {4, {20, brick}}, {5, {15, wedge}}, {6, {10, tetrahedron}}};
  return types;
}

struct Element {
  int number = 0;
  int type = 0;
  std::vector<int> nodes;
};

class FrdReader {
 public:
  explicit FrdReader(std::string path) : path_(std::move(path)) {}

  Result<FemSolution> read();

 private:
  enum class Block { kNone, kNodes, kElements, kDisplacements, kOtherResult };

  Status fail(const std::string& what) const {
    return Status::error(path_ + ":" + std::to_string(line_number_) + ": " + what);
  }
  Status read_line(const std::string& line);
  // A " -1" line of numbers: the number after the key, then `count` values.
  Status numbered_values(const std::string& line, int& number, double* values, int count) const;
  Status finish_element();
  Result<FemSolution> assemble() const;

  std::string path_;
  int line_number_ = 0;
  Block block_ = Block::kNone;
  std::vector<std::pair<int, Eigen::Vector3d>> nodes_;
  std::vector<Element> elements_;
  std::unordered_map<int, Eigen::Vector3d> displacement_block_;  // the block being read
  std::unordered_map<int, Eigen::Vector3d> displacements_;       // the last complete block
  bool has_displacements_ = false;
};

// A Fortran real: "-1.23456E-02", or "1.23456-100" where a three-digit exponent took the 'E''s place.
bool parse_real(std::string field, double& value) {
  const std::size_t sign = field.find_first_of("+-", field.find_first_not_of(" +-"));
  if (field.find_first_of("Ee") == std::string::npos && sign != std::string::npos) field.insert(sign, "E");
  char* end = nullptr;
  value = std::strtod(field.c_str(), &end);
  const char* rest = end;
  return end != field.c_str() && std::isfinite(value) &&
         std::all_of(rest, field.c_str() + field.size(), [](char c) { return c == ' '; });
}

Status FrdReader::numbered_values(const std::string& line, int& number, double* values, int count) const {
  std::size_t at = 3;  // after " -1"
  while (at < line.size() && line[at] == ' ') ++at;
  const std::size_t digits = at;
  while (at < line.size() && std::isdigit(static_cast<unsigned char>(line[at]))) ++at;
  if (at == digits) return fail("expected a node number after '-1'");
  number = std::atoi(line.substr(digits, at - digits).c_str());
  for (int k = 0; k < count; ++k, at += kValueWidth) {
    if (at + kValueWidth > line.size()) {
      return fail("expected " + std::to_string(count) + " values of " + std::to_string(kValueWidth) +
                  " characters after node " + std::to_string(number));
    }
    const std::string field = line.substr(at, kValueWidth);
    if (!parse_real(field, values[k])) {
      return fail("'" + field + "' is not a finite number (node " + std::to_string(number) + ")");
    }
  }
  return {};
}

Status FrdReader::finish_element() {
  if (elements_.empty()) return {};
  const Element& e = elements_.back();
  const int expected = solid_types().at(e.type).node_count;
  if (static_cast<int>(e.nodes.size()) != expected) {
    return fail("element " + std::to_string(e.number) + " of type " + std::to_string(e.type) + " lists " +
                std::to_string(e.nodes.size()) + " nodes; expected " + std::to_string(expected));
  }
  return {};
}

Status FrdReader::read_line(const std::string& line) {
  std::istringstream tokens(line);
  std::string key;
  tokens >> key;
  if (key == "2C") {
    block_ = Block::kNodes;
  } else if (key == "3C") {
    block_ = Block::kElements;
  } else if (key == "-4") {
    std::string name;
    tokens >> name;
    block_ = name == "DISP" ? Block::kDisplacements : Block::kOtherResult;
    displacement_block_.clear();
  } else if (key == "-3") {
    if (block_ == Block::kElements) {
      if (Status done = finish_element(); !done) return done;
    }
    if (block_ == Block::kDisplacements) {
      displacements_ = std::move(displacement_block_);
      has_displacements_ = true;
    }
    block_ = Block::kNone;
  } else if (key == "-1" && block_ == Block::kElements) {
    if (Status done = finish_element(); !done) return done;
    Element element;
    if (!(tokens >> element.number >> element.type)) return fail("expected an element number and type after '-1'");
    if (solid_types().count(element.type) == 0) {
      return fail("element " + std::to_string(element.number) + " has frd type " + std::to_string(element.type) +
                  "; only solid elements are read (types 1-6: bricks, wedges, tetrahedra)");
    }
    elements_.push_back(std::move(element));
  } else if (key == "-2" && block_ == Block::kElements) {
    if (elements_.empty()) return fail("node list '-2' before any element '-1'");
    for (int node = 0; tokens >> node;) elements_.back().nodes.push_back(node);
  } else if (key == "-1" && (block_ == Block::kNodes || block_ == Block::kDisplacements)) {
    int number = 0;
    Eigen::Vector3d values;
    if (Status ok = numbered_values(line, number, values.data(), 3); !ok) return ok;
    if (block_ == Block::kNodes) {
      nodes_.emplace_back(number, values);
    } else {
      displacement_block_[number] = values;
    }
  }
  return {};
}

Result<FemSolution> FrdReader::read() {
  std::ifstream in(path_);
  if (!in) return Status::error(path_ + ": cannot open the CalculiX result file");
  std::array<char, kMaxLineLength + 1> buffer{};
  while (in.getline(buffer.data(), static_cast<std::streamsize>(buffer.size()))) {
    ++line_number_;
    // the count includes the line break, unless the file ended first
    const std::streamsize stored = in.eof() ? in.gcount() : in.gcount() - 1;
    std::string line(buffer.data(), static_cast<std::size_t>(stored));
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (Status ok = read_line(line); !ok) return ok;
  }
  if (in.bad()) return Status::error(path_ + ": cannot read the file (is it a directory?)");
  if (!in.eof()) {
    ++line_number_;
    return fail("a line longer than " + std::to_string(kMaxLineLength) +
                " characters; is this a CalculiX .frd result?");
  }
  if (block_ != Block::kNone) return fail("the file ends inside a block (no closing '-3'); is it complete?");
  return assemble();
}

Result<FemSolution> FrdReader::assemble() const {
  if (nodes_.empty()) return Status::error(path_ + ": no node block (2C); is this a CalculiX .frd result?");
  if (elements_.empty()) return Status::error(path_ + ": no solid elements (block 3C)");
  if (!has_displacements_) {
    return Status::error(path_ + ": no displacements (DISP block); the deck needs '*NODE FILE' with 'U'");
  }
  FemSolution solution;
  const auto n = static_cast<Eigen::Index>(nodes_.size());
  solution.rest_positions.resize(3, n);
  solution.displacements.resize(3, n);
  std::unordered_map<int, int> column_of;
  for (Eigen::Index c = 0; c < n; ++c) {
    const auto& [number, position] = nodes_[static_cast<std::size_t>(c)];
    if (!column_of.emplace(number, static_cast<int>(c)).second) {
      return Status::error(path_ + ": node " + std::to_string(number) + " is defined twice");
    }
    const auto u = displacements_.find(number);
    if (u == displacements_.end()) {
      return Status::error(path_ + ": node " + std::to_string(number) + " has no value in the last DISP block");
    }
    solution.node_ids.push_back(number);
    solution.rest_positions.col(c) = position;
    solution.displacements.col(c) = u->second;
  }

  // a face is outside when one element alone has it; faces are keyed by their sorted corners
  std::map<std::array<int, 4>, std::pair<int, std::vector<int>>> faces;
  for (const Element& e : elements_) {
    std::vector<int> columns;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int node : e.nodes) {
      const auto c = column_of.find(node);
      if (c == column_of.end()) {
        return Status::error(path_ + ": element " + std::to_string(e.number) + " uses node " + std::to_string(node) +
                             ", which the node block does not define");
      }
      columns.push_back(c->second);
      centre += solution.rest_positions.col(c->second);
    }
    centre /= static_cast<double>(columns.size());
    for (const std::vector<int>& corners : solid_types().at(e.type).faces) {
      std::vector<int> face;
      for (int k : corners) face.push_back(columns[static_cast<std::size_t>(k)]);
      // turn the face to point away from its element, whatever the order convention
      const Eigen::Vector3d a = solution.rest_positions.col(face[0]);
      const Eigen::Vector3d normal =
          (solution.rest_positions.col(face[1]) - a).cross(solution.rest_positions.col(face[2]) - a);
      if (normal.dot(a - centre) < 0) std::reverse(face.begin(), face.end());
      std::array<int, 4> key{-1, -1, -1, -1};
      std::copy(face.begin(), face.end(), key.begin());
      std::sort(key.begin(), key.end());
      auto& entry = faces[key];
      ++entry.first;
      entry.second = face;
    }
  }
  std::vector<std::array<int, 3>> triangles;
  for (const auto& [key, entry] : faces) {
    if (entry.first != 1) continue;
    const std::vector<int>& f = entry.second;
    triangles.push_back({f[0], f[1], f[2]});
    if (f.size() == 4) triangles.push_back({f[0], f[2], f[3]});
  }
  solution.surface.resize(3, static_cast<Eigen::Index>(triangles.size()));
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    solution.surface.col(static_cast<Eigen::Index>(t)) << triangles[t][0], triangles[t][1], triangles[t][2];
  }
  return solution;
}

}  // namespace

Result<FemSolution> read_calculix_frd(const std::string& path) { return FrdReader(path).read(); }

}  // namespace cubespring
