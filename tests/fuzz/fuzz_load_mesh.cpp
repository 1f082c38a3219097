// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// libFuzzer target: load_mesh on arbitrary bytes written as a file of the extension in
// FUZZ_EXTENSION (default .ply), the way a user's file reaches assimp. Debian's assimp is not
// instrumented: a fault inside it shows as a crash, not as coverage. scripts/fuzz.sh builds and
// runs it.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include "cubespring/mesh/load_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string extension = std::getenv("FUZZ_EXTENSION") ? std::getenv("FUZZ_EXTENSION") : ".ply";
  static const std::string path = "/tmp/cubespring_fuzz_" + std::to_string(getpid()) + extension;
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  // the COLLADA and glTF readers' own time limit well inside libFuzzer's -timeout, so that a hang
  // the limit stops reads as the error it is, and only one outside it as a hang
  cubespring::LoadOptions options;
  options.reader_seconds = 2.0;
  (void)cubespring::load_mesh(path, options);
  return 0;
}
