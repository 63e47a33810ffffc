// Every subcommand on damaged input: exit 2 and one line naming the file and what is wrong
// (issue 35 item 5), never a traceback or exit 0. And output errors are not ignored.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "../test_support.hpp"

namespace fs = std::filesystem;
using camdyn_test::slurp;

namespace {

const std::string kCli = CAMDYN_CLI_PATH;

struct Out {
  int status = -1;
  std::string err;
};

class DamagedInput : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("camdyn_damaged_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "d");
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }
  Out camdyn(const std::string& args, const std::string& out = "/dev/null") {
    const std::string cmd = "cd '" + dir_.string() + "' && '" + kCli + "' " + args + " >" + out + " 2>err.txt";
    const int raw = std::system(cmd.c_str());
    Out o;
    o.status = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    o.err = slurp(dir_ / "err.txt");
    return o;
  }
  void put(const std::string& name, const std::string& text) { std::ofstream(dir_ / "d" / name, std::ios::binary) << text; }
  /// `camdyn report d`: exit 2, one line, naming `what`.
  void expect_report_refuses(const std::string& what) {
    const Out o = camdyn("report d");
    EXPECT_EQ(o.status, 2) << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    EXPECT_EQ(o.err.find("Traceback"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find(what), std::string::npos) << o.err;
  }
  fs::path dir_;
};

const char* kHistory = "t,theta,u_c,v_c,a_c,contact_force,gap,in_contact,kinetic,potential,work_cam,dissipated\n";
const char* kRow = "0,0,0,0,0,1,0,1,0,0,0,0\n";

}  // namespace

TEST_F(DamagedInput, ReportOnASummaryThatIsAList) {
  put("summary.json", "[1, 2, 3]\n");
  put("history.csv", std::string(kHistory) + kRow);
  expect_report_refuses("a JSON list, expected an object");
}

TEST_F(DamagedInput, ReportOnASummaryWithWrongTypes) {
  put("summary.json", "{\"finished\": \"yes\", \"t_end\": 1}\n");
  put("history.csv", std::string(kHistory) + kRow);
  expect_report_refuses("key 'finished' = \"yes\": expected bool");
  put("summary.json", "{\"finished\": true, \"options\": [1]}\n");
  expect_report_refuses("key 'options'");
}

TEST_F(DamagedInput, ReportOnABinaryHistory) {
  put("summary.json", "{\"finished\": true}\n");
  put("history.csv", std::string("t,x\n\x01\x02\0\xff\xfe", 9));
  expect_report_refuses("history.csv: a binary file");
  put("history.csv", std::string(kHistory) + "\xff\xfe,1\n");
  expect_report_refuses("not UTF-8");
}

TEST_F(DamagedInput, ReportOnAHeaderOnlyHistory) {
  put("summary.json", "{\"finished\": false}\n");
  put("history.csv", kHistory);
  expect_report_refuses("a header and 0 rows");
}

TEST_F(DamagedInput, SceneResolvedToAFullDeviceFails) {
  // Was: exit 0 with nothing written.
  const Out o = camdyn("scene --resolved", "/dev/full");
  EXPECT_NE(o.status, 0);
  EXPECT_NE(o.err.find("cannot write"), std::string::npos) << o.err;
  EXPECT_EQ(camdyn("scene --keys", "/dev/full").status, 1);
}

TEST_F(DamagedInput, SceneKeysWithABadSceneErrors) {
  // Was: the bad scene argument ignored.
  Out o = camdyn("scene --keys nonexistent.toml");
  EXPECT_EQ(o.status, 2) << o.err;
  EXPECT_NE(o.err.find("nonexistent.toml"), std::string::npos) << o.err;
  o = camdyn("scene --keys --set cam.speed_rev_s=-x");
  EXPECT_EQ(o.status, 2) << o.err;
  EXPECT_EQ(camdyn("scene --keys").status, 0);
}
