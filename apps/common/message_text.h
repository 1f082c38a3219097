// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// What the command line shows of a user's arguments inside an error message: one line and short,
// so that the message stays the line or two that scripts read (an argument of kilobytes, or one
// with a line break, was echoed whole).
#pragma once

#include <cstddef>
#include <string>

namespace cubespring::app {

/// `text` with its control characters escaped (\n, \t, \xHH) and, beyond `max_chars`, cut with
/// "... (N characters)" (never inside an escape or a UTF-8 character).
std::string shown_argument(const std::string& text, std::size_t max_chars = 60);

/// A message that may quote arguments whole (CLI11's): its control characters escaped, each word
/// (a run without spaces) longer than 80 characters cut to 60 with "...", and the whole cut to
/// 300 characters the same way (CLI11 lists every argument it did not expect).
std::string bounded_message(const std::string& message);

}  // namespace cubespring::app
