// camdyn — follower-lift tables in CSV (include/camdyn/cam.hpp: LiftTable; docs/cam_laws.md
// "Lift tables"): export from any cam, import with checks naming line and column.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/lift_table.hpp"
#include "cam/follower_geometry.hpp"
#include "cam/format.hpp"

namespace camdyn {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kDeg = kTwoPi / 360.0;

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  std::istringstream in(line);
  while (std::getline(in, cur, ',')) out.push_back(trim(cur));
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}
}  // namespace

LiftTable lift_table_of(const Cam& cam, int points) {
  if (points < 4) throw SceneError("lift_table_of", 0, "points", std::to_string(points), "must be >= 4");
  LiftTable t;
  double xmin = INFINITY;
  std::vector<CamPoint> p(static_cast<std::size_t>(points));
  for (int i = 0; i < points; ++i) {
    p[std::size_t(i)] = cam.evaluate(kTwoPi * i / points);
    xmin = std::min(xmin, p[std::size_t(i)].X_C);
  }
  const CamExtremum lo = cam_extremum(cam, [](const CamPoint& q) { return q.X_C; }, false);
  if (!std::isnan(lo.value)) xmin = std::min(xmin, lo.value);
  for (int i = 0; i < points; ++i) {
    const CamPoint& q = p[std::size_t(i)];
    t.angle_deg.push_back(360.0 * i / points);
    t.lift.push_back(q.X_C - xmin);
    t.dlift_ddeg.push_back(q.dX_dtheta * kDeg);
    t.d2lift_ddeg2.push_back(q.d2X_dtheta2 * kDeg * kDeg);
  }
  return t;
}

std::string lift_table_csv(const LiftTable& t) {
  const bool d = !t.dlift_ddeg.empty();
  std::string out = d ? "angle_deg,lift,dlift_ddeg,d2lift_ddeg2\n" : "angle_deg,lift\n";
  for (std::size_t i = 0; i < t.angle_deg.size(); ++i) {
    out += fmt_num(t.angle_deg[i]) + "," + fmt_num(t.lift[i]);
    if (d) out += "," + fmt_num(t.dlift_ddeg[i]) + "," + fmt_num(t.d2lift_ddeg2[i]);
    out += "\n";
  }
  return out;
}

LiftTable parse_lift_table_csv(const std::string& text, const std::string& source) {
  LiftTable t;
  std::istringstream in(text);
  std::string line;
  int lineno = 0, ncol = 0, last = 0;
  std::vector<std::string> names;
  while (std::getline(in, line)) {
    ++lineno;
    const std::string s = trim(line);
    if (s.empty() || s[0] == '#') continue;
    const std::vector<std::string> f = split(s);
    if (ncol == 0) {
      names = f;
      const bool two = f.size() == 2 && f[0] == "angle_deg" && f[1] == "lift";
      const bool four = f.size() == 4 && f[0] == "angle_deg" && f[1] == "lift" && f[2] == "dlift_ddeg" &&
                        f[3] == "d2lift_ddeg2";
      if (!two && !four)
        throw SceneError(source, lineno, "header", s,
                         "must be angle_deg,lift or angle_deg,lift,dlift_ddeg,d2lift_ddeg2");
      ncol = int(f.size());
      continue;
    }
    if (int(f.size()) != ncol)
      throw SceneError(source, lineno, "row", s,
                       "must have " + std::to_string(ncol) + " numbers (got " + std::to_string(f.size()) + ")");
    double v[4] = {0, 0, 0, 0};
    for (int k = 0; k < ncol; ++k) {
      const std::string& x = f[std::size_t(k)];
      const char* b = x.data();
      const char* e = b + x.size();
      if (b != e && *b == '+') ++b;
      const auto r = std::from_chars(b, e, v[k]);
      if (r.ec != std::errc() || r.ptr != e || !std::isfinite(v[k]))
        throw SceneError(source, lineno, names[std::size_t(k)], x, "must be a finite number");
    }
    if (!t.angle_deg.empty() && !(v[0] > t.angle_deg.back()))
      throw SceneError(source, lineno, "angle_deg", fmt_num(v[0]),
                       "angles must be strictly increasing (line " + std::to_string(last) + " has " +
                           fmt_num(t.angle_deg.back()) + ")");
    if (!t.angle_deg.empty() && !(v[0] - t.angle_deg.front() < 360.0))
      throw SceneError(source, lineno, "angle_deg", fmt_num(v[0]),
                       "the table must span less than 360° (first angle " + fmt_num(t.angle_deg.front()) + ")");
    t.angle_deg.push_back(v[0]);
    t.lift.push_back(v[1]);
    if (ncol == 4) {
      t.dlift_ddeg.push_back(v[2]);
      t.d2lift_ddeg2.push_back(v[3]);
    }
    last = lineno;
  }
  if (ncol == 0) throw SceneError(source, lineno, "header", "", "no header line (angle_deg,lift)");
  if (t.angle_deg.size() < 4)
    throw SceneError(source, lineno, "lift", std::to_string(t.angle_deg.size()) + " rows",
                     "a lift table needs at least 4 rows");
  return t;
}

LiftTable read_lift_table_csv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError("<cam>", 0, "cam.lift_table", "\"" + path + "\"", "cannot read the lift-table file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_lift_table_csv(ss.str(), path);
}

namespace detail {
std::shared_ptr<const MotionLaw> law_of(const CamSpec& spec) {
  if (spec.profile != CamProfileKind::Table) return std::make_shared<MotionLaw>(MotionLaw::parse(spec.law));
  if (spec.lift_table.empty())
    throw SceneError("<cam>", 0, "cam.lift_table", "\"\"", "cam.profile = \"table\" needs the lift-table CSV file");
  const LiftTable t = read_lift_table_csv(spec.lift_table);
  return std::make_shared<MotionLaw>(
      MotionLaw::from_table(t.angle_deg, t.lift, t.dlift_ddeg, t.d2lift_ddeg2, "cam.lift_table"));
}
}  // namespace detail

}  // namespace camdyn
