// camdyn — the numbers the README and the docs quote are the generated ones: every
// <!-- headline SCENE VERSUS -->TEXT<!-- /headline --> quote in README.md and
// docs/background/performance.md equals the `quoted` column of the row (SCENE, VERSUS) of
// docs/bench/generated/headlines.csv, written by scripts/regenerate_docs_numbers.sh from
// the bench's own headlines.csv files; the generated files carry their stamp (commit and
// date). No run and no timing here: the test reads files.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../test_support.hpp"

namespace {

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

/// One CSV line split at commas (the generated files replace commas inside fields).
std::vector<std::string> fields(const std::string& line) { return camdyn_test::split(line, ','); }

const std::string kRoot = CAMDYN_SOURCE_DIR;

}  // namespace

TEST(DocHeadlines, QuotedHeadlinesEqualTheGeneratedOnes) {
  const std::string gen = kRoot + "/docs/bench/generated/headlines.csv";
  std::ifstream f(gen);
  ASSERT_TRUE(f.good()) << gen << " missing: run scripts/regenerate_docs_numbers.sh --quick";
  std::string line;
  ASSERT_TRUE(std::getline(f, line));
  const std::vector<std::string> head = fields(line);
  std::map<std::string, size_t> col;
  for (size_t i = 0; i < head.size(); ++i) col[head[i]] = i;
  for (const char* c : {"scene", "versus", "quoted", "verdict"}) ASSERT_TRUE(col.count(c)) << c;
  std::map<std::pair<std::string, std::string>, std::string> quoted;
  while (std::getline(f, line)) {
    if (line.empty()) continue;
    const auto r = fields(line);
    ASSERT_EQ(r.size(), head.size()) << line;
    quoted[{r[col["scene"]], r[col["versus"]]}] = r[col["quoted"]];
  }
  // The headlines: Lee against penalty on A, the stiff bar, B2, OHC and OHV, and
  // against the event method on every case.
  for (const char* sc : {"A", "stiff", "B2", "ohc", "ohv"}) {
    EXPECT_TRUE(quoted.count({sc, "penalty"})) << "no generated headline " << sc << " penalty";
    EXPECT_TRUE(quoted.count({sc, "event"})) << "no generated headline " << sc << " event";
  }

  const std::regex marker("<!-- headline (\\S+) (\\S+) -->([^<]*)<!-- /headline -->");
  int n_readme = 0;
  for (const char* doc : {"README.md", "docs/background/performance.md"}) {
    const std::string text = read_text(kRoot + "/" + doc);
    ASSERT_FALSE(text.empty()) << doc;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), marker); it != std::sregex_iterator(); ++it) {
      const std::string scene = (*it)[1], versus = (*it)[2], said = (*it)[3];
      if (std::string(doc) == "README.md") ++n_readme;
      auto q = quoted.find({scene, versus});
      ASSERT_NE(q, quoted.end()) << doc << " quotes a headline " << scene << " " << versus
                                 << " that headlines.csv does not have";
      EXPECT_EQ(said, q->second) << doc << ": headline " << scene << " " << versus
                                 << " is stale (scripts/regenerate_docs_numbers.sh --quote rewrites it)";
    }
  }
  // The README quotes the goal headlines (A and the stiff bar against penalty) at least.
  EXPECT_GE(n_readme, 2);
}

TEST(DocHeadlines, GeneratedFilesCarryTheirStamp) {
  const std::string stamp = read_text(kRoot + "/docs/bench/generated/STAMP.md");
  const std::regex commit("at commit [0-9a-f]{7,}(\\+uncommitted)? on \\d{4}-\\d\\d-\\d\\dT");
  EXPECT_TRUE(std::regex_search(stamp, commit)) << "STAMP.md names no commit and date";
  for (const char* md : {"headlines.md", "wp_A/work_precision.md", "wp_stiff/work_precision.md"}) {
    const std::string text = read_text(kRoot + "/docs/bench/generated/" + md);
    ASSERT_FALSE(text.empty()) << md;
    EXPECT_TRUE(std::regex_search(text, commit)) << md << " carries no stamp";
  }
}
