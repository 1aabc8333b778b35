// `servoloop sweep SPEC.yaml --out DIR [--jobs N] [--scheduler ADDRESS]
// [--resume]`: many episodes of a launch file over a grid or random samples
// of parameters, on this machine's cores or on a Dask distributed cluster.
// The sweep itself is the Python package's (python/servoloop/sweep.py, where
// Dask lives); this command runs it with the Python the package was built
// for, so that `servoloop sweep` works like every other command.
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "command_registry.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/executable_path.hpp"

namespace servoloop::cli {
namespace {

namespace fs = std::filesystem;

struct SweepOptions {
  std::string spec;
  std::string out;
  unsigned jobs = 0;  // 0: every core
  std::string scheduler;
  bool resume = false;
};

#ifdef SERVOLOOP_PYTHON_EXECUTABLE
// The folder holding the servoloop package: build/python next to build/bin,
// or the install's dist-packages next to <prefix>/bin.
fs::path pythonPackageRoot() {
  std::error_code error;
  const fs::path bin = executableDirectory(error);
  if (error) throw Error("sweep: cannot find the servoloop executable's folder: " + error.message());
  for (const fs::path& root : {bin.parent_path() / "python", bin.parent_path() / SERVOLOOP_PYTHON_INSTALL_DIR}) {
    if (fs::exists(root / "servoloop" / "sweep.py")) return root;
  }
  throw Error(fmt::format("sweep: the servoloop Python package is not next to {} (build it: cmake --build build, "
                          "or install it: cmake --install build)",
                          bin.string()));
}
#endif

[[noreturn]] void runSweep(const SweepOptions& options) {
#ifndef SERVOLOOP_PYTHON_EXECUTABLE
  (void)options;
  throw Error("sweep: this servoloop was built without its Python package (apt install python3-dev pybind11-dev, "
              "then configure and build again)");
#else
  const fs::path root = pythonPackageRoot();
  std::string path = root.string();
  if (const char* existing = std::getenv("PYTHONPATH"); existing != nullptr && *existing != '\0') {
    path += std::string(":") + existing;
  }
  ::setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<std::string> args{SERVOLOOP_PYTHON_EXECUTABLE, "-m", "servoloop.sweep", options.spec, "--out", options.out};
  if (options.jobs > 0) args.insert(args.end(), {"--jobs", std::to_string(options.jobs)});
  if (!options.scheduler.empty()) args.insert(args.end(), {"--scheduler", options.scheduler});
  if (options.resume) args.emplace_back("--resume");
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  ::execv(argv.front(), argv.data());
  throw Error(fmt::format("sweep: cannot run {}: {}", SERVOLOOP_PYTHON_EXECUTABLE, std::strerror(errno)));
#endif
}

void addSweepCommand(CLI::App& root) {
  auto options = std::make_shared<SweepOptions>();
  CLI::App* sweep = root.add_subcommand(
      "sweep", "Run many episodes over a grid or random samples of parameters, locally or on a Dask cluster "
               "(docs/sweeps.md)");
  sweep->add_option("SPEC", options->spec, "Sweep spec (YAML: launch, duration, vary, random, measure, ...)")
      ->required()
      ->type_name("SPEC.yaml");
  sweep->add_option("--out", options->out, "Folder for episodes.csv and the plots")->required()->type_name("DIR");
  sweep->add_option("--jobs", options->jobs, "Episodes at once on this machine (default: every core)")
      ->check(CLI::Range(1u, 4096u));
  sweep->add_option("--scheduler", options->scheduler,
                    "A running Dask distributed scheduler to send the episodes to")
      ->type_name("tcp://HOST:PORT");
  sweep->add_flag("--resume", options->resume, "Run only the episodes DIR/episodes.csv does not have yet");
  sweep->callback([options] { runSweep(*options); });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(17, servoloop::cli::addSweepCommand)
