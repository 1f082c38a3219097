// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring: calibrated soft-tissue simulation from the command line.
#include <iostream>
#include <exception>
#include <map>

#include "commands.h"
#include "run_benchmarks.h"

// Under LeakSanitizer: OSMesa keeps about 100 bytes per context that OSMesaDestroyContext does
// not free, inside libOSMesa; not ours to fix, and not to be reported as ours.
// Its count is not printed either: an error message stays the one line that scripts read.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOSMesa.so\n"; }
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }

int main(int argc, char** argv) {
  if (argc >= 2 && cubespring::app::is_benchmark_command(argv[1])) return cubespring::app::run_benchmarks(argc, argv);
  CLI::App app{"cubespring: calibrated cube mass-spring soft tissue (SI units throughout)"};
  app.set_version_flag("--version", "cubespring 0.1.0");
  std::map<std::string, cubespring::app::Command> commands;
  app.footer(cubespring::app::benchmark_commands_help());
  commands["measure"] = cubespring::app::add_measure_command(app);
  commands["voxelize"] = cubespring::app::add_voxelize_command(app);
#ifdef CUBESPRING_HAS_DEMO
  commands["run"] = cubespring::app::add_run_command(app);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    // one line that names the argument, then a non-zero exit
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
  // the commands report bad input themselves; what escapes them (memory exhausted, say) still
  // ends as one line and a non-zero exit, not an abort
  try {
    for (auto& [name, run] : commands) {
      if (app.got_subcommand(name)) return run();
    }
#ifdef CUBESPRING_HAS_DEMO
    return commands["run"]();  // no subcommand: the default scene (the surgical demo)
#else
    std::cout << app.help();
    return 0;
#endif
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
