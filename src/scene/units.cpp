// camdyn — the scene keys in a valve-train designer's units (issue 28): cam.speed_rpm with
// cam.rpm_of (camshaft or engine crankshaft rpm) instead of cam.speed_rev_s, and
// run.revolutions instead of run.t_end. They are converted when the scene is loaded, in the
// TOML table, before the key table reads it: the Scene holds rev/s and seconds only, and
// to_toml writes those (docs/reference/scene_keys.md, docs/guide/valve_trains.md).
#include <cmath>
#include <string>
#include <vector>

#include "scene/detail.hpp"

namespace camdyn::scene_detail {

namespace {

constexpr const char* kRpmRule =
    "needs cam.rpm_of = \"camshaft\" (rpm of the camshaft) or \"engine\" (rpm of a four-stroke engine's "
    "crankshaft: the camshaft turns at half of it)";

double number(const toml::node& n, const std::string& file, int line, const std::string& key) {
  double v = 0;
  if (auto i = n.as_integer())
    v = static_cast<double>(i->get());
  else if (auto d = n.as_floating_point())
    v = d->get();
  else
    fail(file, line, key, fmt_node(n), "must be a number");
  if (!std::isfinite(v) || std::fabs(v) > 1e50)
    fail(file, line, key, fmt_node(n), "must be a finite number, at most 1e50 in absolute value");
  return v;
}

}  // namespace

const std::vector<std::string>& designer_unit_keys() {
  static const std::vector<std::string> k{"cam.speed_rpm", "cam.rpm_of", "run.revolutions"};
  return k;
}

DesignerUnits read_designer_units(const toml::table& root, const std::string& file, bool use_lines) {
  auto line = [&](const toml::node& n) { return use_lines ? line_of(n) : 0; };
  DesignerUnits u;
  const toml::table* cam = root.get_as<toml::table>("cam");
  const toml::table* run = root.get_as<toml::table>("run");

  // ---- cam.speed_rpm + cam.rpm_of → cam.speed_rev_s
  if (cam) {
    const toml::node* rpm = cam->get("speed_rpm");
    const toml::node* of = cam->get("rpm_of");
    if (of && !rpm)
      fail(file, line(*of), "cam.rpm_of", fmt_node(*of), "is only used with cam.speed_rpm");
    if (rpm) {
      const double v = number(*rpm, file, line(*rpm), "cam.speed_rpm");
      if (const toml::node* rev = cam->get("speed_rev_s"))
        fail(file, line(*rpm), "cam.speed_rpm", fmt_node(*rpm),
             "cannot be given with cam.speed_rev_s (= " + fmt_node(*rev) +
                 "): give the cam speed once, in rpm or in rev/s");
      if (!of) fail(file, line(*rpm), "cam.speed_rpm", fmt_node(*rpm), kRpmRule);
      const auto name = of->as_string();
      if (!name || (name->get() != "camshaft" && name->get() != "engine"))
        fail(file, line(*of), "cam.rpm_of", fmt_node(*of), one_of({"camshaft", "engine"}));
      // camshaft rpm / 60 = rev/s; engine (crankshaft) rpm / 120: a four-stroke camshaft
      // turns once per two crankshaft revolutions. One division, so 3000 engine rpm is
      // exactly 25 rev/s.
      u.speed_rev_s = name->get() == "engine" ? v / 120.0 : v / 60.0;
      u.rpm_per_rev_s = name->get() == "engine" ? 120.0 : 60.0;
      u.speed_line = line(*rpm);
    }
  }

  // ---- run.revolutions (→ run.t_end once the speed is known: apply_designer_units)
  if (run) {
    if (const toml::node* rev = run->get("revolutions")) {
      const double n = number(*rev, file, line(*rev), "run.revolutions");
      if (const toml::node* t = run->get("t_end"))
        fail(file, line(*rev), "run.revolutions", fmt_node(*rev),
             "cannot be given with run.t_end (= " + fmt_node(*t) +
                 "): give the run's length once, in revolutions or in time");
      if (!(n > 0)) fail(file, line(*rev), "run.revolutions", fmt_node(*rev), "must be > 0");
      u.revolutions = n;
      u.revolutions_text = fmt_node(*rev);
      u.revolutions_line = line(*rev);
    }
  }
  return u;
}

void apply_designer_units(const DesignerUnits& u, Scene& s, const std::string& file, LineMap& lines) {
  if (u.speed_rev_s) {
    s.cam.speed_rev_s = *u.speed_rev_s;
    s.rpm_per_rev_s = u.rpm_per_rev_s;
    lines["cam.speed_rev_s"] = u.speed_line;
  }
  if (u.revolutions) {
    if (!s.cam.speed_table_t.empty() || !s.cam.speed_table_rev_s.empty())
      fail(file, u.revolutions_line, "run.revolutions", u.revolutions_text,
           "needs a constant cam speed (a speed table is given): give run.t_end");
    if (s.cam.speed_rev_s == 0.0)
      fail(file, u.revolutions_line, "run.revolutions", u.revolutions_text,
           "needs a cam speed other than 0 (cam.speed_rev_s = 0)");
    // The run's own limit (Simulator: one Poincaré sample per revolution), named here under
    // the key the user gave rather than under the cam speed it is divided by.
    if (!(*u.revolutions <= 1e7))
      fail(file, u.revolutions_line, "run.revolutions", u.revolutions_text,
           "must be <= 1e7 revolutions (one Poincaré sample is kept per revolution)");
    s.run.t_end = *u.revolutions / std::fabs(s.cam.speed_rev_s);
    lines["run.t_end"] = u.revolutions_line;
  }
}

bool is_designer_unit_key(std::string_view key) {
  for (const auto& k : designer_unit_keys())
    if (key == k) return true;
  return false;
}

void drop_replaced_by_designer_units(toml::table& root, const std::vector<std::string>& keys_set) {
  auto set = [&](const char* k) {
    for (const auto& s : keys_set)
      if (s == k) return true;
    return false;
  };
  if (set("cam.speed_rpm") && !set("cam.speed_rev_s"))
    if (auto* cam = root.get_as<toml::table>("cam")) cam->erase("speed_rev_s");
  if (set("run.revolutions") && !set("run.t_end"))
    if (auto* run = root.get_as<toml::table>("run")) run->erase("t_end");
}

}  // namespace camdyn::scene_detail
