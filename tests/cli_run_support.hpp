// The camdyn CLI run from a test in a directory of its own: exit status, stdout, stderr
// (tests/cli/test_cli.cpp, tests/study/sweep_test_support.hpp).
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "test_support.hpp"

namespace camdyn_test {

struct CliResult {
  int status = -1;  ///< the exit status; -1 when the command did not exit normally
  std::string out, err;
};

/// `s` as one shell word (in single quotes).
inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'')
      q += "'\\''";
    else
      q += c;
  }
  return q + "'";
}

/// Run "CLI ARGS" in `dir` (ARGS is shell text; stdin empty); its stdout and stderr pass
/// through dir/stdout.txt and dir/stderr.txt.
inline CliResult run_cli(const std::string& cli, const std::filesystem::path& dir, const std::string& args) {
  const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = "cd " + shell_quote(dir.string()) + " && " + shell_quote(cli) + " " + args + " >" +
                          shell_quote(out.string()) + " 2>" + shell_quote(err.string()) + " </dev/null";
  const int raw = std::system(cmd.c_str());
  CliResult r;
  r.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

}  // namespace camdyn_test
