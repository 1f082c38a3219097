// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT

#include "calculix_common.h"

#include <cctype>

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

constexpr const char* kLogName = "ccx.log";
constexpr int kLogTailLines = 12;

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

std::string format_double_impl(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), "%.9g", value);
  return buffer;
}

// ccx reads each numeric field through its first 20 characters only
// (Fortran f20.0): longer text is cut silently, and a cut exponent is an
// input error. %.13g never exceeds 20 characters ("-1.234567890123e-100").
constexpr const char* kDeckNumber = "%.13g";

std::string deck_number_impl(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), kDeckNumber, value);
  return buffer;
}

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

// The last "total force (fx,fy,fz) for set <set> and time T" block: its line of three numbers,
// at the end of the step (T = 1).
std::string parse_total_force(const fs::path& dat_path, const std::string& set, Eigen::Vector3d& force) {
  std::ifstream dat(dat_path);
  if (!dat) return "cannot open ccx output " + dat_path.string();
  std::string upper_set = set;
  for (char& c : upper_set) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  std::string line;
  int line_number = 0;
  bool in_block = false, found = false;
  double time = NAN;
  while (std::getline(dat, line)) {
    ++line_number;
    std::string upper = line;
    for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (upper.find("TOTAL FORCE (FX,FY,FZ) FOR SET " + upper_set + " ") != std::string::npos) {
      const std::size_t at = upper.find("TIME");
      std::istringstream header(at == std::string::npos ? std::string() : line.substr(at + 4));
      std::string token;
      header >> token;
      if (!parse_fortran_double(token, time)) {
        return dat_path.string() + ":" + std::to_string(line_number) + ": unreadable time in '" + line + "'";
      }
      in_block = true;
      continue;
    }
    if (!in_block) continue;
    std::istringstream fields(line);
    std::string tokens[3];
    int count = 0;
    while (count < 3 && fields >> tokens[count]) ++count;
    if (count == 0) continue;
    in_block = false;
    if (count != 3 || !parse_fortran_double(tokens[0], force.x()) || !parse_fortran_double(tokens[1], force.y()) ||
        !parse_fortran_double(tokens[2], force.z())) {
      return dat_path.string() + ":" + std::to_string(line_number) + ": unreadable total force '" + line + "'";
    }
    found = true;
  }
  if (!found) return dat_path.string() + ": no total force block for set " + set;
  if (!(std::abs(time - 1.0) < 1e-6)) {
    return dat_path.string() + ": the last total force of set " + set + " is at time " + format_double_impl(time) +
           ", not at the end of the step (1)";
  }
  return {};
}

CcxResult fail(std::string message) {
  CcxResult result;
  result.error = std::move(message);
  return result;
}

CcxResult run(const std::string& work_dir_text, const std::string& job, const std::string& deck, int corner_count,
              const std::string& total_force_set) {
  // work folder, cleared of the outputs of an earlier run so a failed run can never be mistaken
  // for a good one; absolute, so the shell's cd can never take it for an option
  std::error_code ec;
  const fs::path work_dir = fs::absolute(fs::path(work_dir_text), ec);
  if (ec) return fail("bad work_dir " + work_dir_text + ": " + ec.message());
  fs::create_directories(work_dir, ec);
  if (ec || !fs::is_directory(work_dir)) {
    return fail("cannot create work_dir " + work_dir.string() + ": " +
                (ec ? ec.message() : std::string("not a directory")));
  }
  const fs::path inp_path = work_dir / (job + ".inp");
  const fs::path dat_path = work_dir / (job + ".dat");
  const fs::path log_path = work_dir / kLogName;
  fs::remove(dat_path, ec);
  fs::remove(log_path, ec);
  {
    std::ofstream inp(inp_path, std::ios::binary | std::ios::trunc);
    if (!inp) return fail("cannot write " + inp_path.string());
    inp << deck;
    inp.close();
    if (!inp) return fail("error writing " + inp_path.string());
  }

  // OMP_NUM_THREADS sets ccx's threads for assembly and SPOOLES (4.1 s with one, 3.4 s with two
  // for a 32x8x8 beam); the project's machines have two cores
  const std::string command = "cd " + shell_quote(work_dir.string()) + " && OMP_NUM_THREADS=2 ccx -i " + job +
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
    return fail("ccx failed (" + how + ") in " + work_dir.string() + "; last lines of " + log_path.string() + ":" +
                read_log_tail(log_path));
  }

  CcxResult result;
  double time = NAN;
  if (std::string problem = parse_dat(dat_path, corner_count, result.corner_displacement, time); !problem.empty()) {
    return fail(problem + "; last lines of " + log_path.string() + ":" + read_log_tail(log_path));
  }
  // the step's period is 1: an earlier time means ccx stopped short
  if (!(std::abs(time - 1.0) < 1e-6)) {
    return fail("last displacement block in " + dat_path.string() + " is at time " + format_double_impl(time) +
                ", not at the end of the step (1); last lines of " + log_path.string() + ":" + read_log_tail(log_path));
  }
  if (!total_force_set.empty()) {
    if (std::string problem = parse_total_force(dat_path, total_force_set, result.total_force); !problem.empty()) {
      return fail(problem);
    }
  }
  return result;
}

}  // namespace

std::string deck_number(double value) { return deck_number_impl(value); }
std::string format_double(double value) { return format_double_impl(value); }

CcxResult run_ccx(const std::string& work_dir, const std::string& job, const std::string& deck, int corner_count,
                  const std::string& total_force_set) {
  try {
    return run(work_dir, job, deck, corner_count, total_force_set);
  } catch (const std::exception& error) {
    return fail(std::string("unexpected failure: ") + error.what());
  } catch (...) {
    return fail("unexpected failure");
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
