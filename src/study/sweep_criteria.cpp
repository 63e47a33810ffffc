// camdyn — the acceptance criteria over a finished sweep, from its sweep.csv
// (sweep_criteria_table(), include/camdyn/designer.hpp).
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "camdyn/designer.hpp"

namespace camdyn {

// ---- the criteria over a sweep --------------------------------------------------------

namespace {
// One CSV line's fields (quoted fields with "" escapes).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> f(1);
  bool q = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (q) {
      if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') f.back() += '"', ++i;
      else if (ch == '"') q = false;
      else f.back() += ch;
    } else if (ch == '"') {
      q = true;
    } else if (ch == ',') {
      f.emplace_back();
    } else if (ch != '\r') {
      f.back() += ch;
    }
  }
  return f;
}
}  // namespace

std::vector<SweepCriterion> sweep_criteria_table(const std::string& csv_path) {
  std::ifstream in(csv_path);
  if (!in) throw std::runtime_error("cannot read " + csv_path);
  std::string line;
  if (!std::getline(in, line)) return {};
  const std::vector<std::string> head = csv_fields(line);
  std::vector<SweepCriterion> out;
  std::vector<std::size_t> col;
  const std::string pre = "criterion_", post = "_pass";
  for (std::size_t i = 0; i < head.size(); ++i) {
    const std::string& h = head[i];
    if (h.size() > pre.size() + post.size() && h.compare(0, pre.size(), pre) == 0 &&
        h.compare(h.size() - post.size(), post.size(), post) == 0) {
      SweepCriterion c;
      c.name = h.substr(pre.size(), h.size() - pre.size() - post.size());
      out.push_back(c);
      col.push_back(i);
    }
  }
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> f = csv_fields(line);
    const double key = f.empty() ? NAN : std::strtod(f[0].c_str(), nullptr);
    for (std::size_t k = 0; k < out.size(); ++k) {
      SweepCriterion& c = out[k];
      ++c.points;
      const std::string v = col[k] < f.size() ? f[col[k]] : "";
      if (v.empty()) continue;
      ++c.judged;
      if (v == "0") {
        ++c.failed;
        if (std::isnan(c.first_failure) || key < c.first_failure) c.first_failure = key;
      }
    }
  }
  return out;
}

}  // namespace camdyn
