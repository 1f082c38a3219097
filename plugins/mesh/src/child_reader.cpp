// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "child_reader.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <new>
#include <optional>
#include <sstream>

// GCC says -fsanitize=address by __SANITIZE_ADDRESS__, clang (before 17) by __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define CUBESPRING_CHILD_UNDER_ASAN
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CUBESPRING_CHILD_UNDER_ASAN
#endif
#endif
#ifdef CUBESPRING_CHILD_UNDER_ASAN
#include <sanitizer/common_interface_defs.h>
#endif

namespace cubespring {
namespace {

#ifdef CUBESPRING_CHILD_UNDER_ASAN
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif

// Under AddressSanitizer the child's own faults (an allocation of gigabytes a malformed file asks
// for, an overflow in the reader) are the reader's error, which the parent reports with the file's
// name: the child prints no sanitizer report, and a fuzzer's death callback, which the fork
// inherits, does not save the input as a crash of the caller. (So a fuzz run finds no memory
// error inside assimp's readers that run here: it finds what would crash or hang the caller.)
void quiet_sanitizers_in_child() {
#ifdef CUBESPRING_CHILD_UNDER_ASAN
  __sanitizer_set_death_callback(nullptr);
  const int quiet = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (quiet >= 0) __sanitizer_set_report_fd(reinterpret_cast<void*>(static_cast<std::intptr_t>(quiet)));
#endif
}

// What the child sends: a letter that says which, then the message or the mesh.
constexpr char kMesh = 'M', kError = 'E';

void put(std::string& out, const void* data, std::size_t size) { out.append(static_cast<const char*>(data), size); }
void put_count(std::string& out, std::uint64_t count) { put(out, &count, sizeof count); }
void put_text(std::string& out, const std::string& text) {
  put_count(out, text.size());
  out += text;
}

std::string encode(const Result<TriangleMesh>& read) {
  std::string out;
  if (!read.ok()) {
    out += kError;
    put_text(out, read.message());
    return out;
  }
  const TriangleMesh& mesh = read.value();
  out += kMesh;
  put_count(out, static_cast<std::uint64_t>(mesh.vertices.cols()));
  put_count(out, static_cast<std::uint64_t>(mesh.triangles.cols()));
  put_count(out, mesh.parts.size());
  put(out, mesh.vertices.data(), sizeof(double) * static_cast<std::size_t>(mesh.vertices.size()));
  put(out, mesh.triangles.data(), sizeof(int) * static_cast<std::size_t>(mesh.triangles.size()));
  for (const MeshPart& part : mesh.parts) {
    put_text(out, part.name);
    put_text(out, part.material_name);
    put(out, &part.first_triangle, sizeof part.first_triangle);
    put(out, &part.triangle_count, sizeof part.triangle_count);
  }
  return out;
}

// Reads what encode() wrote; each take() fails when the bytes end first (the child stopped
// part way), so a count is never trusted beyond the bytes that are there.
class Decoder {
 public:
  explicit Decoder(const std::string& bytes) : bytes_(bytes) {}
  bool take(void* data, std::size_t size) {
    if (size > bytes_.size() - at_) return false;
    std::memcpy(data, bytes_.data() + at_, size);
    at_ += size;
    return true;
  }
  bool count(std::uint64_t& value, std::size_t bytes_each) {
    return take(&value, sizeof value) && value <= (bytes_.size() - at_) / bytes_each;
  }
  bool text(std::string& value) {
    std::uint64_t size = 0;
    if (!count(size, 1)) return false;
    value.assign(bytes_, at_, size);
    at_ += size;
    return true;
  }
  bool finished() const { return at_ == bytes_.size(); }

 private:
  const std::string& bytes_;
  std::size_t at_ = 0;
};

// The child's answer, or nothing when it is incomplete.
std::optional<Result<TriangleMesh>> decode(const std::string& bytes) {
  Decoder in(bytes);
  char kind = 0;
  if (!in.take(&kind, 1)) return std::nullopt;
  if (kind == kError) {
    std::string message;
    if (!in.text(message) || !in.finished()) return std::nullopt;
    return Result<TriangleMesh>(Status::error(message));
  }
  std::uint64_t vertices = 0, triangles = 0, parts = 0;
  if (kind != kMesh || !in.count(vertices, 3 * sizeof(double)) || !in.count(triangles, 3 * sizeof(int)) ||
      !in.count(parts, 1)) {
    return std::nullopt;
  }
  TriangleMesh mesh;
  mesh.vertices.resize(3, static_cast<Eigen::Index>(vertices));
  mesh.triangles.resize(3, static_cast<Eigen::Index>(triangles));
  if (!in.take(mesh.vertices.data(), 3 * sizeof(double) * vertices) ||
      !in.take(mesh.triangles.data(), 3 * sizeof(int) * triangles)) {
    return std::nullopt;
  }
  mesh.parts.resize(parts);
  for (MeshPart& part : mesh.parts) {
    if (!in.text(part.name) || !in.text(part.material_name) ||
        !in.take(&part.first_triangle, sizeof part.first_triangle) ||
        !in.take(&part.triangle_count, sizeof part.triangle_count)) {
      return std::nullopt;
    }
  }
  if (!in.finished()) return std::nullopt;
  return Result<TriangleMesh>(std::move(mesh));
}

void write_all(int fd, const std::string& bytes) {
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    written += static_cast<std::size_t>(n);
  }
}

std::string gigabytes(std::uint64_t bytes) {
  std::ostringstream out;
  out.precision(3);
  out << static_cast<double>(bytes) / 1e9 << " GB";
  return out.str();
}

// This process's address space [bytes] (/proc/self/statm: its size in pages first).
std::optional<std::uint64_t> address_space_in_use() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  const long page_size = ::sysconf(_SC_PAGESIZE);
  if (!(statm >> pages) || page_size <= 0) return std::nullopt;
  return pages * static_cast<std::uint64_t>(page_size);
}

[[noreturn]] void run_child(int out, const std::string& path, const std::string& reader, const ChildLimits& limits,
                            const std::function<Result<TriangleMesh>()>& read) {
  // the address space it has from the caller, and memory_bytes more: the caller's own (a
  // simulator's gigabytes) must not count against the reader. AddressSanitizer maps terabytes of
  // shadow memory, which a limit on the address space would deny it.
  if (limits.memory_bytes > 0 && !kAddressSanitizer) {
    if (const std::optional<std::uint64_t> used = address_space_in_use()) {
      const rlimit limit{*used + limits.memory_bytes, *used + limits.memory_bytes};
      (void)setrlimit(RLIMIT_AS, &limit);
    }
  }
  // a fault ends the child by its signal, which the parent reports: not by the handlers a
  // sanitizer or fuzzer installed in the caller, which would report it as the caller's own
  for (const int signal : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT}) std::signal(signal, SIG_DFL);
  quiet_sanitizers_in_child();
  std::string bytes;
  try {
    bytes = encode(read());
  } catch (const std::bad_alloc&) {
    bytes = encode(Status::error(path + ": " + reader + " needs more than the memory limit of " +
                                 gigabytes(limits.memory_bytes) + " for it: is the file malformed?"));
  } catch (const std::exception& e) {
    bytes = encode(Status::error(path + ": " + reader + " failed: " + e.what()));
  }
  write_all(out, bytes);
  ::_exit(0);  // not exit(): the parent's atexit handlers and stdio buffers are the parent's
}

}  // namespace

Result<TriangleMesh> read_in_child(const std::string& path, const std::string& reader, const ChildLimits& limits,
                                   const std::function<Result<TriangleMesh>()>& read) {
  std::array<int, 2> pipe_ends{};
  // not inherited by a program another thread of the caller starts meanwhile, which would hold
  // the pipe open after the child is done
  if (::pipe2(pipe_ends.data(), O_CLOEXEC) != 0) {
    return Status::error(path + ": cannot start a process for " + reader + ": " + std::strerror(errno));
  }
  const pid_t child = ::fork();
  if (child < 0) {
    const int error = errno;
    ::close(pipe_ends[0]);
    ::close(pipe_ends[1]);
    return Status::error(path + ": cannot start a process for " + reader + ": " + std::strerror(error));
  }
  if (child == 0) {
    ::close(pipe_ends[0]);
    run_child(pipe_ends[1], path, reader, limits, read);
  }
  ::close(pipe_ends[1]);

  using Clock = std::chrono::steady_clock;
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limits.seconds));
  std::string bytes;
  bool timed_out = false;
  std::array<char, 1 << 16> buffer{};
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd ready{pipe_ends[0], POLLIN, 0};
    const int polled = ::poll(&ready, 1, static_cast<int>(std::min<long long>(left, 1 << 30)));
    if (polled < 0 && errno == EINTR) continue;
    if (polled == 0) {
      timed_out = true;
      break;
    }
    const ssize_t n = ::read(pipe_ends[0], buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // the end: the child has answered, or is gone
    bytes.append(buffer.data(), static_cast<std::size_t>(n));
  }
  ::close(pipe_ends[0]);
  if (timed_out) ::kill(child, SIGKILL);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }

  std::ostringstream message;
  message.precision(3);
  message << path << ": " << reader;
  if (timed_out) {
    message << " took more than " << limits.seconds << " s on it and was stopped: is the file malformed?";
    return Status::error(message.str());
  }
  if (std::optional<Result<TriangleMesh>> answer = decode(bytes)) return std::move(*answer);
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    message << " crashed on it (signal " << signal << ", " << strsignal(signal) << "): the file is malformed";
  } else {
    message << " stopped before it had read it (exit code " << (WIFEXITED(status) ? WEXITSTATUS(status) : -1)
            << "): the file is malformed";
  }
  return Status::error(message.str());
}

}  // namespace cubespring
