// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <optional>
#include <string>
#include <utility>

// The error contract, for every part of cubespring:
// - Data a caller can get wrong (a value out of range, a file, a scene's key, the settings of a
//   step or a solve) is refused with a message naming the argument or key, the value and what
//   was expected: a Status or Result here, StepStatus::kInvalidInput for a step,
//   StaticReport::message for the static solver. Nothing was read past an end or changed.
// - StepStatus::kUnstable and kSolverFailed say what the simulation did with valid data (a node
//   too fast, CG short of its tolerance), never that the settings were wrong.
// - A few calls that return a value have preconditions on the shape of what they are given,
//   which the caller controls and can check first; like std::vector::at, they throw naming it
//   rather than read past an array's end. std::invalid_argument: compute_forces(), the energies
//   and StiffnessAssembler::assemble given arrays without one column per node
//   (check_state_and_loads() first). std::length_error: StiffnessAssembler, max_frequency() and
//   max_stable_time_step() for a body too large for a sparse matrix's int indices
//   (check_stiffness_size() first). The library's own paths from data (Stepper::step,
//   solve_static, the Bullet plugin, the scene runtime, the command line) check first and report
//   those as a status: no file, key or flag reaches an exception.
// - Beyond those, only std::bad_alloc crosses the API.
// - The library's own invariants are CUBESPRING_ASSERT (src/invariant.h), checked in the dev and
//   asan builds; no input reaches them.
namespace cubespring {

/// Outcome of an operation on outside input: success, or a message that names the value at fault,
/// what was expected, and (where known) the file.
class [[nodiscard]] Status {
 public:
  Status() = default;
  static Status error(std::string message) { return Status(std::move(message)); }

  bool ok() const { return !message_.has_value(); }
  explicit operator bool() const { return ok(); }
  /// The error message; empty when ok().
  const std::string& message() const {
    static const std::string kEmpty;
    return message_ ? *message_ : kEmpty;
  }

 private:
  explicit Status(std::string message) : message_(std::move(message)) {}
  std::optional<std::string> message_;
};

/// A value or the Status that explains why there is none.
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}          // NOLINT: implicit on purpose, like std::expected
  Result(Status status) : status_(std::move(status)) {}  // NOLINT

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  const Status& status() const { return status_; }
  const std::string& message() const { return status_.message(); }

  T& value() & { return *value_; }
  const T& value() const& { return *value_; }
  T&& value() && { return std::move(*value_); }
  T& operator*() & { return *value_; }
  const T& operator*() const& { return *value_; }
  T* operator->() { return &*value_; }
  const T* operator->() const { return &*value_; }

 private:
  std::optional<T> value_;
  Status status_;
};

}  // namespace cubespring
