// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring-bench: the benchmarks, each a subcommand that prints a table (or JSON with --json).
// `cubespring bench...` hands its arguments to this program.
#include <map>
#include <string>

#include "commands.h"

// Under LeakSanitizer: OSMesa keeps about 100 bytes per context that OSMesaDestroyContext does
// not free, inside libOSMesa (bench-render draws); not ours to report.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOSMesa.so\n"; }
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }

int main(int argc, char** argv) {
  CLI::App app{"cubespring-bench: cubespring's benchmarks (SI units throughout); `cubespring bench...` runs them too"};
  app.set_version_flag("--version", "cubespring-bench 0.1.0");
  std::map<std::string, cubespring::app::Command> commands;
  commands["bench"] = cubespring::app::add_bench_command(app);
  commands["bench-voxelize"] = cubespring::app::add_bench_voxelize_command(app);
  commands["bench-layout"] = cubespring::app::add_bench_layout_command(app);
#ifdef CUBESPRING_HAS_BULLET
  commands["bench-bullet"] = cubespring::app::add_bench_bullet_command(app);
#endif
#ifdef CUBESPRING_HAS_BULLET_PLUGIN
  commands["bench-contact"] = cubespring::app::add_bench_contact_command(app);
#endif
#ifdef CUBESPRING_HAS_DEMO
  commands["bench-render"] = cubespring::app::add_bench_render_command(app);
#endif
  return cubespring::app::parse_and_run(app, argc, argv, commands);
}
