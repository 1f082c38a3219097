// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "json_fields.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace cubespring::scene {
namespace {

using nlohmann::json;

// JSON's own names, as a user reading the file sees the value
std::string type_name(const json& value) {
  if (value.is_number()) return "number";
  return value.type_name();
}

std::string format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

JsonFields::JsonFields(const JsonWithLines& document, std::string source, std::string pointer, std::string where)
    : document_(&document),
      value_(&document.value.at(json::json_pointer(pointer))),
      source_(std::move(source)),
      pointer_(std::move(pointer)),
      where_(std::move(where)) {}

std::string JsonFields::name_of(const std::string& key) const { return where_.empty() ? key : where_ + "." + key; }

Status JsonFields::error(const std::string& key, const std::string& message) const {
  const int line = document_->line_of(child_pointer(pointer_, key));
  const std::string place = where_.empty() ? "" : " in " + quote_for_message(where_);
  return Status::error(source_ + ":" + std::to_string(line) + ": " + quote_for_message(key) + place + " " + message);
}

int JsonFields::line() const { return document_->line_of(pointer_); }

Status JsonFields::error_here(const std::string& message) const {
  return Status::error(source_ + ":" + std::to_string(document_->line_of(pointer_)) + ": " + message);
}

Status JsonFields::type_error(const std::string& key, const char* expected) const {
  const json* value = member(key);
  return error(key, std::string("must be ") + expected + ", got " + (value ? type_name(*value) : "nothing"));
}

Status JsonFields::check_keys(const std::vector<std::string>& allowed) const {
  if (!value_->is_object()) {
    const std::string what = where_.empty() ? "the scene" : quote_for_message(where_);
    return error_here(what + " must be an object, got " + type_name(*value_));
  }
  for (const auto& [key, value] : value_->items()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string expected;
    for (const std::string& name : allowed) expected += (expected.empty() ? "" : ", ") + name;
    const int line = document_->line_of(child_pointer(pointer_, key));
    const std::string place = where_.empty() ? "the scene" : quote_for_message(where_);
    return Status::error(source_ + ":" + std::to_string(line) + ": unknown key " + quote_for_message(key) + " in " +
                         place + " (expected one of: " + expected + ")");
  }
  return {};
}

const json* JsonFields::member(const std::string& key) const {
  if (!value_->is_object()) return nullptr;
  const auto found = value_->find(key);
  return found == value_->end() ? nullptr : &*found;
}

bool JsonFields::has(const std::string& key) const { return member(key) != nullptr; }

std::vector<std::string> JsonFields::keys() const {
  std::vector<std::string> names;
  if (value_->is_object()) {
    for (const auto& [key, value] : value_->items()) names.push_back(key);
  }
  return names;
}

Status JsonFields::number(const std::string& key, double& out) const {
  const json* value = member(key);
  if (value == nullptr) return {};
  if (!value->is_number()) return type_error(key, "a number");
  out = value->get<double>();
  return {};
}

Status JsonFields::positive(const std::string& key, double& out) const {
  double value = out;
  if (Status status = number(key, value); !status) return status;
  if (has(key) && !(value > 0.0)) return error(key, "must be > 0, got " + format(value));
  out = value;
  return {};
}

Status JsonFields::non_negative(const std::string& key, double& out) const {
  double value = out;
  if (Status status = number(key, value); !status) return status;
  if (has(key) && !(value >= 0.0)) return error(key, "must be >= 0, got " + format(value));
  out = value;
  return {};
}

Status JsonFields::fraction(const std::string& key, double& out) const {
  double value = out;
  if (Status status = number(key, value); !status) return status;
  if (has(key) && !(value >= 0.0 && value <= 1.0)) return error(key, "must be in [0, 1], got " + format(value));
  out = value;
  return {};
}

Status JsonFields::integer(const std::string& key, int& out, int min, int max) const {
  const json* value = member(key);
  if (value == nullptr) return {};
  if (!value->is_number()) return type_error(key, "a whole number");
  const double number = value->get<double>();
  if (number != std::floor(number)) return error(key, "must be a whole number, got " + format(number));
  if (number < min || number > max) {
    return error(key, "must be in " + std::to_string(min) + ".." + std::to_string(max) + ", got " + format(number));
  }
  out = static_cast<int>(number);
  return {};
}

Status JsonFields::boolean(const std::string& key, bool& out) const {
  const json* value = member(key);
  if (value == nullptr) return {};
  if (!value->is_boolean()) return type_error(key, "true or false");
  out = value->get<bool>();
  return {};
}

Status JsonFields::string(const std::string& key, std::string& out) const {
  const json* value = member(key);
  if (value == nullptr) return {};
  if (!value->is_string()) return type_error(key, "a string");
  out = value->get<std::string>();
  return {};
}

Status JsonFields::vector3(const std::string& key, Eigen::Vector3d& out) const {
  const json* value = member(key);
  if (value == nullptr) return {};
  const bool three_numbers = value->is_array() && value->size() == 3 &&
                             std::all_of(value->begin(), value->end(), [](const json& v) { return v.is_number(); });
  if (!three_numbers) {
    const std::string got =
        value->is_array() ? "an array of " + std::to_string(value->size()) + " values" : type_name(*value);
    return error(key, "must be an array of 3 numbers [x, y, z], got " + got);
  }
  for (int i = 0; i < 3; ++i) out[i] = (*value)[static_cast<std::size_t>(i)].get<double>();
  return {};
}

Status JsonFields::quaternion(const std::string& key, Eigen::Quaterniond& out) const {
  const json* value = member(key);
  if (value == nullptr) return {};
  const bool four_numbers = value->is_array() && value->size() == 4 &&
                            std::all_of(value->begin(), value->end(), [](const json& v) { return v.is_number(); });
  if (!four_numbers) {
    const std::string got =
        value->is_array() ? "an array of " + std::to_string(value->size()) + " values" : type_name(*value);
    return error(key, "must be a quaternion [w, x, y, z], got " + got);
  }
  Eigen::Quaterniond q((*value)[0].get<double>(), (*value)[1].get<double>(), (*value)[2].get<double>(),
                       (*value)[3].get<double>());
  if (!(q.norm() > 1e-12)) return error(key, "must be a non-zero quaternion [w, x, y, z]");
  out = q.normalized();
  return {};
}

Result<JsonFields> JsonFields::object(const std::string& key) const {
  const json* value = member(key);
  if (value == nullptr || !value->is_object()) return type_error(key, "an object");
  return JsonFields(*document_, source_, child_pointer(pointer_, key), name_of(key));
}

Result<std::vector<JsonFields>> JsonFields::objects(const std::string& key) const {
  const json* value = member(key);
  if (value == nullptr || !value->is_array()) return type_error(key, "an array");
  std::vector<JsonFields> elements;
  for (std::size_t i = 0; i < value->size(); ++i) {
    const std::string index = std::to_string(i);
    JsonFields element(*document_, source_, child_pointer(child_pointer(pointer_, key), index),
                       name_of(key) + "[" + index + "]");
    if (!(*value)[i].is_object()) {
      return element.error_here("\"" + name_of(key) + "[" + index + "]\" must be an object, got " +
                                type_name((*value)[i]));
    }
    elements.push_back(std::move(element));
  }
  return elements;
}

}  // namespace cubespring::scene
