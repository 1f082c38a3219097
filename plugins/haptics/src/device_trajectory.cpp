// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/haptics/device_trajectory.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace cubespring::haptics {
namespace {

constexpr int kColumns = 8;
const char* const kColumnNames[kColumns] = {"time_s", "x_m", "y_m", "z_m", "qw", "qx", "qy", "qz"};

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

// The value as the message shows it: cut short, one line.
std::string shown(const std::string& value) {
  std::string shown = value.size() > 40 ? value.substr(0, 40) + "..." : value;
  std::replace_if(
      shown.begin(), shown.end(), [](char c) { return c < ' '; }, '?');
  return "\"" + shown + "\"";
}

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(trimmed(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

bool read_number(const std::string& text, double& out) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno != ERANGE && std::isfinite(out);
}

}  // namespace

const char* const DeviceTrajectory::kHeader = "time_s,x_m,y_m,z_m,qw,qx,qy,qz";

Result<DeviceTrajectory> DeviceTrajectory::parse(const std::string& text, const std::string& source) {
  std::vector<DeviceSample> samples;
  std::stringstream lines(text);
  std::string line;
  int number = 0;
  bool header_read = false;
  while (std::getline(lines, line)) {
    ++number;
    const std::string where = source + ":" + std::to_string(number) + ": ";
    const std::string content = trimmed(line);
    if (content.empty() || content[0] == '#') continue;
    const std::vector<std::string> fields = fields_of(content);
    if (!header_read) {
      for (int c = 0; c < kColumns; ++c) {
        if (static_cast<int>(fields.size()) != kColumns || fields[c] != kColumnNames[c])
          return Status::error(where + "the first line must be the header " + kHeader + ", not " + shown(content));
      }
      header_read = true;
      continue;
    }
    if (static_cast<int>(fields.size()) != kColumns)
      return Status::error(where + std::to_string(fields.size()) + " values, expected " + std::to_string(kColumns) +
                           " (" + kHeader + ")");
    double values[kColumns];
    for (int c = 0; c < kColumns; ++c) {
      if (!read_number(fields[c], values[c]))
        return Status::error(where + kColumnNames[c] + " " + shown(fields[c]) + " is not a finite number");
    }
    DeviceSample sample;
    sample.time = values[0];
    sample.position = Eigen::Vector3d(values[1], values[2], values[3]);
    const Eigen::Quaterniond q(values[4], values[5], values[6], values[7]);
    // its length must be a number: 1e200 squared is not
    if (!(q.norm() > 1e-9 && std::isfinite(q.squaredNorm())))
      return Status::error(where + "the orientation qw, qx, qy, qz must be neither zero nor larger than 1e150");
    sample.orientation = q.normalized();
    if (!samples.empty() && !(sample.time > samples.back().time))
      return Status::error(where + "time_s " + fields[0] + " must be later than the line before's");
    if (!(sample.position.cwiseAbs().maxCoeff() <= 1000.0)) {
      char position[96];
      std::snprintf(position, sizeof position, "(%.4g, %.4g, %.4g)", values[1], values[2], values[3]);
      return Status::error(where + "the position " + position + " is more than 1 km from the origin: is it in metres?");
    }
    samples.push_back(sample);
  }
  if (!header_read) return Status::error(source + ": empty; expected the header " + kHeader + " and samples");
  if (samples.empty()) return Status::error(source + ": no samples after the header");
  return DeviceTrajectory(std::move(samples));
}

Result<DeviceTrajectory> DeviceTrajectory::load(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return Status::error(path + ": not a file that can be read");
  const std::uintmax_t size = fs::file_size(path, error);
  if (error || size > kMaxBytes)
    return Status::error(path + ": larger than " + std::to_string(kMaxBytes / 1000000) + " MB, or unreadable");
  std::ifstream file(path, std::ios::binary);
  if (!file) return Status::error(path + ": cannot be opened");
  std::stringstream text;
  text << file.rdbuf();
  return parse(text.str(), path);
}

DeviceState DeviceTrajectory::at(double t) const {
  DeviceState state;
  state.time = t;
  const auto after = std::upper_bound(samples_.begin(), samples_.end(), t,
                                      [](double time, const DeviceSample& s) { return time < s.time; });
  if (after == samples_.begin() || after == samples_.end()) {
    const DeviceSample& held = after == samples_.begin() ? samples_.front() : samples_.back();
    state.pose.linear() = held.orientation.toRotationMatrix();
    state.pose.translation() = held.position;
    return state;
  }
  const DeviceSample& a = *(after - 1);
  const DeviceSample& b = *after;
  const double span = b.time - a.time;
  const double s = (t - a.time) / span;
  state.pose.translation() = (1 - s) * a.position + s * b.position;
  state.pose.linear() = a.orientation.slerp(s, b.orientation).toRotationMatrix();
  state.linear_velocity = (b.position - a.position) / span;
  Eigen::Quaterniond turn = b.orientation * a.orientation.conjugate();
  if (turn.w() < 0) turn.coeffs() = -turn.coeffs();
  const Eigen::AngleAxisd angle_axis(turn);
  state.angular_velocity = angle_axis.angle() / span * angle_axis.axis();
  return state;
}

}  // namespace cubespring::haptics
