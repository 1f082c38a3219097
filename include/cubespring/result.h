// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <optional>
#include <string>
#include <utility>

// The error contract, for every part of cubespring:
// - Input a caller can get wrong (a value out of range, arrays that do not fit the body, a file)
//   is refused with a message naming the argument or key, the value and what was expected: a
//   Status or Result here, StepStatus::kInvalidInput for a step, StaticReport::message for the
//   static solver. Nothing was read past an end or changed.
// - StepStatus::kUnstable and kSolverFailed say what the simulation did with valid input (a node
//   too fast, CG short of its tolerance), never that the settings were wrong.
// - The library's own invariants are CUBESPRING_ASSERT (src/invariant.h), checked in the dev and
//   asan builds; no input reaches them.
// - The exceptions that are left are listed on Status below.
namespace cubespring {

/// Outcome of an operation on outside input: success, or a message that names the value at fault,
/// what was expected, and (where known) the file. No exceptions cross the API but std::bad_alloc;
/// from a body too large for a sparse matrix's int indices, StiffnessAssembler's and
/// max_stable_time_step's std::length_error; and from compute_forces() and the energies given
/// arrays that do not fit the body (their column counts), std::invalid_argument naming them
/// (Stepper::step reports those as a status).
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
