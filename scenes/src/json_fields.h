// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Typed, checked reads of the members of one JSON object: every error names the key, where it
// is, and its line ("scene.json:7: \"young_modulus\" in \"organ\" must be a number, got string").
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cubespring/result.h"
#include "json_lines.h"

namespace cubespring::scene {

class JsonFields {
 public:
  /// The object at `pointer` of `document`; `where` names it in messages ("organ.materials",
  /// "tools[0]"), empty for the top level.
  JsonFields(const JsonWithLines& document, std::string source, std::string pointer, std::string where);

  /// Checks that the value is an object whose keys are all in `allowed`.
  Status check_keys(const std::vector<std::string>& allowed) const;
  bool has(const std::string& key) const;
  /// The object's keys, sorted (JSON objects keep no order).
  std::vector<std::string> keys() const;

  // Each read leaves `out` unchanged when the key is absent (its default stays).
  Status number(const std::string& key, double& out) const;
  Status positive(const std::string& key, double& out) const;      ///< > 0
  Status non_negative(const std::string& key, double& out) const;  ///< >= 0
  Status fraction(const std::string& key, double& out) const;      ///< in [0, 1]
  Status integer(const std::string& key, int& out, int min, int max) const;
  Status boolean(const std::string& key, bool& out) const;
  Status string(const std::string& key, std::string& out) const;
  Status vector3(const std::string& key, Eigen::Vector3d& out) const;
  /// [w, x, y, z], normalised; a zero quaternion is an error.
  Status quaternion(const std::string& key, Eigen::Quaterniond& out) const;

  /// The member `key`, which must be an object.
  Result<JsonFields> object(const std::string& key) const;
  /// The member `key`, which must be an array of objects: one JsonFields per element.
  Result<std::vector<JsonFields>> objects(const std::string& key) const;

  /// "SOURCE:LINE: "key" in "where" `message`" (LINE of the key).
  Status error(const std::string& key, const std::string& message) const;
  /// "SOURCE:LINE: `message`" (LINE of this object).
  Status error_here(const std::string& message) const;
  /// The line where this object's key (or the object) is.
  int line() const;
  /// The name of the member `key` in messages ("organ.materials").
  std::string name_of(const std::string& key) const;

 private:
  const nlohmann::json* member(const std::string& key) const;
  Status type_error(const std::string& key, const char* expected) const;

  const JsonWithLines* document_;
  const nlohmann::json* value_;
  std::string source_;
  std::string pointer_;
  std::string where_;
};

}  // namespace cubespring::scene
