// camdyn — the cam.law string: segments separated by ';' (or new lines), each
//   KIND DURATION_DEG [RISE] [c0 c1 … (poly)] [k=… m=… ks=… speed_rev_s=… (polydyne)]
// e.g. "ramp 10 0.1; cycloidal 60 8.9; dwell 20; cycloidal 60 -8.9; ramp 10 -0.1; dwell 200".
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/motion_law.hpp"
#include "camdyn/cam_spec.hpp"
#include "camdyn/scene_error.hpp"

namespace camdyn {

namespace {

struct KindName {
  const char* name;
  MotionSegmentKind kind;
};
constexpr KindName kKinds[] = {
    {"dwell", MotionSegmentKind::Dwell},       {"ramp", MotionSegmentKind::Ramp},
    {"harmonic", MotionSegmentKind::Harmonic}, {"shm", MotionSegmentKind::Harmonic},
    {"cycloidal", MotionSegmentKind::Cycloidal}, {"poly345", MotionSegmentKind::Poly345},
    {"poly4567", MotionSegmentKind::Poly4567}, {"poly", MotionSegmentKind::Poly},
    {"modtrap", MotionSegmentKind::ModTrap},   {"modified_trapezoid", MotionSegmentKind::ModTrap},
    {"modsine", MotionSegmentKind::ModSine},   {"modified_sine", MotionSegmentKind::ModSine},
    {"polydyne", MotionSegmentKind::Polydyne}};

std::string kind_list() {
  std::string s;
  for (const KindName& k : kKinds) {
    if (!s.empty()) s += ", ";
    s += k.name;
  }
  return s;
}

bool to_number(const std::string& t, double* v) {
  if (t.empty()) return false;
  errno = 0;
  char* end = nullptr;
  *v = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size() && errno != ERANGE;
}

}  // namespace

MotionLaw MotionLaw::parse(const std::string& text, const std::string& key) {
  auto fail = [&](const std::string& rule) { throw SceneError("<cam>", 0, key, "\"" + text + "\"", rule); };
  std::string norm = text;
  for (char& c : norm)
    if (c == '\n') c = ';';
  std::vector<MotionSegment> segs;
  std::stringstream all(norm);
  std::string part;
  std::size_t idx = 0;
  while (std::getline(all, part, ';')) {
    for (char& c : part)
      if (c == ',' || c == '\t' || c == '\r') c = ' ';
    std::stringstream ss(part);
    std::vector<std::string> tok;
    for (std::string t; ss >> t;) tok.push_back(t);
    if (tok.empty()) continue;
    ++idx;
    const std::string where = "segment " + std::to_string(idx) + " ('" + part.substr(part.find_first_not_of(' ')) + "')";
    MotionSegment s;
    bool found = false;
    for (const KindName& k : kKinds)
      if (tok[0] == k.name) {
        s.kind = k.kind;
        found = true;
      }
    if (!found) fail(where + ": unknown kind '" + tok[0] + "' (one of: " + kind_list() + ")");
    std::vector<double> nums;
    for (std::size_t i = 1; i < tok.size(); ++i) {
      const std::size_t eq = tok[i].find('=');
      if (eq != std::string::npos) {
        const std::string name = tok[i].substr(0, eq);
        double v;
        if (!to_number(tok[i].substr(eq + 1), &v)) fail(where + ": '" + tok[i] + "' is not NAME=NUMBER");
        if (s.kind != MotionSegmentKind::Polydyne)
          fail(where + ": '" + name + "=' is a polydyne parameter");
        if (name == "k") s.k = v;
        else if (name == "m") s.m = v;
        else if (name == "ks") s.ks = v;
        else if (name == "speed_rev_s") s.speed_rev_s = v;
        else fail(where + ": unknown parameter '" + name + "' (polydyne: k, m, ks, speed_rev_s)");
        continue;
      }
      double v;
      if (!to_number(tok[i], &v)) fail(where + ": '" + tok[i] + "' is not a number");
      nums.push_back(v);
    }
    const bool dwell = s.kind == MotionSegmentKind::Dwell;
    if (nums.empty()) fail(where + ": give the duration in degrees");
    s.duration_deg = nums[0];
    if (dwell) {
      if (nums.size() != 1) fail(where + ": a dwell takes only its duration ('dwell DURATION_DEG')");
    } else {
      if (nums.size() < 2) fail(where + ": give the duration [deg] and the rise (negative: a fall)");
      s.rise = nums[1];
      if (s.kind == MotionSegmentKind::Poly)
        s.coefficients.assign(nums.begin() + 2, nums.end());
      else if (nums.size() != 2)
        fail(where + ": takes DURATION_DEG RISE only");
    }
    if (s.kind == MotionSegmentKind::Polydyne && (s.k == 0 || s.m == 0 || s.speed_rev_s == 0))
      fail(where + ": polydyne needs k=, m= and speed_rev_s= (ks= optional, default 0)");
    segs.push_back(s);
  }
  return MotionLaw(std::move(segs), key);
}

}  // namespace camdyn
