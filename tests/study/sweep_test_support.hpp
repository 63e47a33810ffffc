// The CLI's sweep and jump commands run in a fresh directory per test (SweepTest) and
// their CSV files read back by column (tests/study/test_sweep.cpp, test_jump_speed.cpp).
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "../cli_run_support.hpp"
#include "../test_support.hpp"

namespace camdyn_test {

namespace fs = std::filesystem;

const std::string kCli = CAMDYN_CLI_PATH;

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string::npos) nl = text.size();
    if (nl > pos) out.push_back(text.substr(pos, nl - pos));
    pos = nl + 1;
  }
  return out;
}

// Columns of a sweep.csv as name → values (the message column is left as text).
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::size_t col(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  double num(std::size_t r, const std::string& name) const { return std::strtod(rows[r][col(name)].c_str(), nullptr); }
};
inline Csv read_csv(const fs::path& p) {
  Csv c;
  const auto lines = lines_of(slurp(p));
  if (lines.empty()) return c;
  c.header = split(lines[0], ',');
  for (std::size_t i = 1; i < lines.size(); ++i) c.rows.push_back(split(lines[i], ','));
  return c;
}

class SweepTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("camdyn_sweep_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }
  using R = CliResult;
  /// Run "camdyn ARGS" in the test's directory.
  R camdyn(const std::string& args) { return run_cli(kCli, dir_, args); }
  fs::path dir_;
};

}  // namespace camdyn_test
