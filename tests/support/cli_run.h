#pragma once
// Runs the patchwork command line as a user runs it, with stdout and stderr captured (the CLI's
// tests; PATCHWORK_CLI names the program).

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/support/temporary_directory.h"

namespace patchwork::testing {

/// What one run printed and returned.
struct CliRun {
  int exit_code;
  std::string out;
  std::string err;
};

/// `s` in single quotes, for a shell command.
inline std::string quote(const std::string& s) { return "'" + s + "'"; }

/// Runs `patchwork ARGS` with stdout and stderr captured in files of `folder`.
inline CliRun run_patchwork(const TemporaryDirectory& folder, const std::string& arguments) {
  const std::filesystem::path out = folder.path() / "stdout.txt";
  const std::filesystem::path err = folder.path() / "stderr.txt";
  const std::string command =
      quote(PATCHWORK_CLI) + " " + arguments + " > " + quote(out.string()) + " 2> " + quote(err.string());
  const int status = std::system(command.c_str());
  CliRun run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return run;
}

}  // namespace patchwork::testing
