// camdyn (private) — the scene validator (validate.cpp: the keys' own rules and the rules
// between keys; validate_network.cpp: the network tables). Every rule names the file, line,
// key, value and what is allowed.
#pragma once

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <utility>
#include <toml++/toml.h>
#include "camdyn/cam.hpp"
#include "scene/detail.hpp"
#include "scene/fields.hpp"
#include "camdyn/scene.hpp"

namespace camdyn {
namespace scene_detail {

constexpr double kMaxTheta0Deg = 1e6;

class Validator {
 public:
  Validator(const Scene& s, const std::string& file, const LineMap& lines) : s_(s), file_(file), lines_(lines) {}

  int line(const std::string& key, const std::string& fallback = "") const {
    auto it = lines_.find(key);
    if (it != lines_.end()) return it->second;
    if (!fallback.empty()) {
      it = lines_.find(fallback);
      if (it != lines_.end()) return it->second;
    }
    // An array element not recorded: use the array's line.
    auto br = key.find('[');
    if (br != std::string::npos) {
      it = lines_.find(key.substr(0, br));
      if (it != lines_.end()) return it->second;
    }
    return 0;
  }

  [[noreturn]] void fail_at(const std::string& key, const std::string& value, const std::string& rule,
                            const std::string& fallback = "") const {
    throw SceneError(file_, line(key, fallback), key, value, rule);
  }

  void finite(const std::string& key, double v) const {
    if (!std::isfinite(v)) fail_at(key, fmt_num(v), "must be a finite number");
    // Issue 25: E = 1e308 or a preload of 1e308 passed and the integrator then failed on
    // the overflowing products. No unit system needs magnitudes beyond 1e50, and products
    // of a few such quantities stay far inside double precision.
    if (std::abs(v) > kMaxMagnitude)
      fail_at(key, fmt_num(v),
              "is not a physical magnitude: must be <= " + fmt_num(kMaxMagnitude) +
                  " in absolute value (products with the scene's other quantities would overflow double precision)");
  }
  void finite(const std::string& key, const std::vector<double>& v) const {
    for (std::size_t i = 0; i < v.size(); ++i) finite(elem(key, i), v[i]);
  }
  void gt(const std::string& key, double v, double lo) const {
    finite(key, v);
    if (!(v > lo)) fail_at(key, fmt_num(v), "must be > " + fmt_num(lo));
  }
  void ge(const std::string& key, double v, double lo) const {
    finite(key, v);
    if (!(v >= lo)) fail_at(key, fmt_num(v), "must be >= " + fmt_num(lo));
  }
  void in(const std::string& key, double v, double lo, double hi) const {
    finite(key, v);
    if (!(v >= lo && v <= hi)) fail_at(key, fmt_num(v), "must be >= " + fmt_num(lo) + " and <= " + fmt_num(hi));
  }
  void int_in(const std::string& key, long long v, long long lo, long long hi) const {
    if (v < lo || v > hi) fail_at(key, std::to_string(v), range_rule(lo, hi));
  }
  static std::string elem(const std::string& key, std::size_t i) { return key + "[" + std::to_string(i) + "]"; }

  /// ≥ 4 values, strictly increasing, span < 360°.
  void angle_table(const std::string& key, const std::vector<double>& a, const std::string& context,
                   const std::string& fallback) const {
    if (a.size() < 4)
      fail_at(key, fmt_vec(a), "must have at least 4 values" + context + " (has " + std::to_string(a.size()) + ")",
              fallback);
    increasing(key, a);
    if (!(a.back() - a.front() < 360.0))
      fail_at(elem(key, a.size() - 1), fmt_num(a.back()),
              "must be < " + key + "[0] + 360 = " + fmt_num(a.front() + 360.0) + " (the table spans less than 360 deg)");
  }
  void increasing(const std::string& key, const std::vector<double>& a) const {
    for (std::size_t i = 1; i < a.size(); ++i)
      if (!(a[i] > a[i - 1]))
        fail_at(elem(key, i), fmt_num(a[i]),
                "must be > " + elem(key, i - 1) + " = " + fmt_num(a[i - 1]) + " (strictly increasing)");
  }
  void same_length(const std::string& key, const std::vector<double>& a, const std::string& ref_key,
                   const std::vector<double>& ref) const {
    if (a.size() != ref.size())
      fail_at(key, fmt_vec(a),
              "must have as many values as " + ref_key + " (" + std::to_string(ref.size()) + "), has " +
                  std::to_string(a.size()),
              ref_key);
  }

  /// Every key's own rule from the key table (fields()).
  void key_rules() const {
    Scene& s = const_cast<Scene&>(s_);  // the accessors are non-const; nothing is written
    for (const Field& f : fields()) {
      const std::string key = f.path();
      switch (f.kind) {
        case FK::Arr:
          finite(key, f.arr(s));
          break;
        case FK::Int:
          int_in(key, f.get_int(s), f.imin, f.imax);
          break;
        case FK::Real: {
          const double v = f.real(s);
          finite(key, v);
          if (f.rule == Rule::Gt && f.lo == 0.0 && v > 0.0 && v < 1.0 / kMaxMagnitude)
            fail_at(key, fmt_num(v),
                    "is not a physical magnitude: must be >= " + fmt_num(1.0 / kMaxMagnitude) +
                        " (its reciprocal would overflow double precision in the scene's products)");
          const bool ok = f.rule == Rule::Finite ? true
                          : f.rule == Rule::Gt   ? v > f.lo
                          : f.rule == Rule::Ge   ? v >= f.lo
                          : f.rule == Rule::In   ? (v >= f.lo && v <= f.hi)
                          : f.rule == Rule::GtLe ? (v > f.lo && v <= f.hi)
                                                 : (v == 0.0 || (v >= f.lo && v <= f.hi));
          if (ok) break;
          const std::string rule =
              f.rule == Rule::Gt   ? "must be > " + fmt_num(f.lo)
              : f.rule == Rule::Ge ? "must be >= " + fmt_num(f.lo)
              : f.rule == Rule::In ? "must be >= " + fmt_num(f.lo) + " and <= " + fmt_num(f.hi)
              : f.rule == Rule::GtLe ? "must be > " + fmt_num(f.lo) + " and <= " + fmt_num(f.hi)
                                     : std::string(f.note);
          fail_at(key, fmt_num(v), rule);
        }
        default:
          break;
      }
    }
  }

  void run() const {
    const Scene& s = s_;
    key_rules();
    // ---- [synthesis] (the rules synthesise_cam_from_valve_lift applies, named by key)
    if (!(std::abs(s.synthesis.valve_end_angle_deg) < 90.0))
      fail_at("synthesis.valve_end_angle_deg", fmt_num(s.synthesis.valve_end_angle_deg), "must be > -90 and < 90");
    if (s.synthesis.lash > 0 && !(s.synthesis.ramp_deg > 0 && s.synthesis.ramp_deg < 180))
      fail_at("synthesis.ramp_deg", fmt_num(s.synthesis.ramp_deg),
              "with synthesis.lash > 0 the lash ramp must be > 0 and < 180 degrees");
    // ---- cam (rules between keys)
    const CamSpec& c = s.cam;
    if (c.profile == CamProfileKind::Points) {
      angle_table("cam.angles_deg", c.angles_deg, "", "cam.profile");
      same_length("cam.radii", c.radii, "cam.angles_deg", c.angles_deg);
      for (std::size_t i = 0; i < c.radii.size(); ++i) gt(elem("cam.radii", i), c.radii[i], 0.0);
    }
    if (c.profile == CamProfileKind::Lift) {
      angle_table("cam.lift_angles_deg", c.lift_angles_deg, " for cam.profile = \"lift\"", "cam.profile");
      same_length("cam.lift", c.lift, "cam.lift_angles_deg", c.lift_angles_deg);
      for (std::size_t i = 0; i < c.lift.size(); ++i)
        if (!(c.base_radius + c.lift[i] > 0))
          fail_at(elem("cam.lift", i), fmt_num(c.lift[i]),
                  "must be > -cam.base_radius = " + fmt_num(-c.base_radius) + " (base_radius + lift > 0)");
    }
    // Motion laws, arc cams and the follower faces (issue 24): their rules live with the
    // geometry (cam.cpp, follower_geometry.cpp); reported here with the scene's file.
    if (c.profile == CamProfileKind::Table && c.lift_table.empty())
      fail_at("cam.lift_table", "\"\"", "cam.profile = \"table\" needs the lift-table CSV file", "cam.profile");
    if (c.profile == CamProfileKind::Law || c.profile == CamProfileKind::Table || c.profile == CamProfileKind::Arc ||
        c.profile == CamProfileKind::Arcs ||
        c.follower_face != FollowerFace::Flat || c.follower_motion != FollowerMotion::Translating) {
      try {
        Cam check(c);
      } catch (const SceneError& e) {
        fail_at(e.key(), e.value(), e.rule());
      }
    }
    // The cam angle θ₀ + ωt is one double: beyond 1e6 deg its spacing (ulp) exceeds 1e-10 rad
    // and grows to whole revolutions at 1e16 deg, so the cam's position is lost.
    if (!(std::abs(c.theta0_deg) <= kMaxTheta0Deg))
      fail_at("cam.theta0_deg", fmt_num(c.theta0_deg),
              "must be within +-" + fmt_num(kMaxTheta0Deg) +
                  " deg: the cam angle theta0 + omega t is one double, and beyond that its resolution is coarser "
                  "than 1e-10 rad (give the angle modulo 360)");
    // Cam friction: a flat face or a roller; a Stribeck curve rises from μ to μ_s. On an
    // oscillating follower the friction's moment about the pivot enters the dynamics (the
    // lock a ≤ μ|b| is the geometry's check, cam/follower_oscillating.cpp).
    if (c.friction_coefficient > 0 || c.friction_static_coefficient > 0) {
      if (c.follower_motion == FollowerMotion::Oscillating && c.follower_face == FollowerFace::Roller &&
          c.roller_slip > 0)
        fail_at("cam.roller_slip", fmt_num(c.roller_slip),
                "a slipping roller is modelled on a translating follower only; on an oscillating follower "
                "(cam.follower_motion = \"oscillating\") the roller rolls: must be 0",
                "cam.follower_motion");
      if (c.follower_motion == FollowerMotion::Oscillating && s.camshaft.present())
        fail_at("cam.friction_coefficient", fmt_num(c.friction_coefficient),
                "cam friction on an oscillating follower with a [camshaft] body is not modelled (the friction's "
                "torque on the shaft's stations is not applied); remove [camshaft] or set 0",
                "camshaft.inertias");
      if (c.follower_face != FollowerFace::Flat && c.follower_face != FollowerFace::Roller)
        fail_at("cam.friction_coefficient", fmt_num(c.friction_coefficient),
                std::string("cam friction needs cam.follower_face = \"flat\" or \"roller\" (the face is \"") +
                    to_string(c.follower_face) + "\")",
                "cam.follower_face");
      if (c.follower_face == FollowerFace::Roller && c.roller_slip > 0 && c.follower_offset != 0)
        fail_at("cam.roller_slip", fmt_num(c.roller_slip),
                "a slipping roller's sliding speed is modelled for an in-line roller: needs cam.follower_offset = 0 "
                "(it is " + fmt_num(c.follower_offset) + ")",
                "cam.follower_offset");
    }
    if (c.friction_stribeck_speed > 0 && !(c.friction_static_coefficient >= c.friction_coefficient))
      fail_at("cam.friction_static_coefficient", fmt_num(c.friction_static_coefficient),
              "must be >= cam.friction_coefficient = " + fmt_num(c.friction_coefficient) +
                  " with a Stribeck curve (cam.friction_stribeck_speed > 0)",
              "cam.friction_stribeck_speed");
    if (c.friction_stribeck_speed == 0 && c.friction_static_coefficient != 0)
      fail_at("cam.friction_static_coefficient", fmt_num(c.friction_static_coefficient),
              "needs cam.friction_stribeck_speed > 0 (without it the friction is the constant "
              "cam.friction_coefficient); must be 0",
              "cam.friction_stribeck_speed");
    if (c.roller_slip != 0.0 && c.follower_face != FollowerFace::Roller)
      fail_at("cam.roller_slip", fmt_num(c.roller_slip),
              std::string("applies to cam.follower_face = \"roller\" only (the face is \"") +
                  to_string(c.follower_face) + "\"); must be 0",
              "cam.follower_face");
    // Keys that do not apply to the chosen follower: refused, not ignored.
    if (c.roller_radius != 0.0 && c.follower_face != FollowerFace::Roller)
      fail_at("cam.roller_radius", fmt_num(c.roller_radius),
              std::string("applies to cam.follower_face = \"roller\" only (the face is \"") + to_string(c.follower_face) +
                  "\"); must be 0",
              "cam.follower_face");
    if (c.follower_motion == FollowerMotion::Translating) {
      const std::pair<const char*, double> pivot_keys[] = {{"cam.pivot_x", c.pivot_x},
                                                           {"cam.pivot_y", c.pivot_y},
                                                           {"cam.arm_length", c.arm_length},
                                                           {"cam.pad_offset", c.pad_offset},
                                                           {"cam.valve_arm", c.valve_arm}};
      for (const auto& [key, v] : pivot_keys)
        if (v != 0.0)
          fail_at(key, fmt_num(v),
                  "applies to cam.follower_motion = \"oscillating\" only (the follower translates); must be 0",
                  "cam.follower_motion");
    }
    if (!(c.eccentricity < c.radius))
      fail_at("cam.eccentricity", fmt_num(c.eccentricity), "must be < cam.radius = " + fmt_num(c.radius));
    if (!c.speed_table_t.empty() || !c.speed_table_rev_s.empty()) {
      same_length("cam.speed_table_rev_s", c.speed_table_rev_s, "cam.speed_table_t", c.speed_table_t);
      if (c.speed_table_t.front() != 0.0)
        fail_at("cam.speed_table_t[0]", fmt_num(c.speed_table_t.front()), "must be 0 (the speed table starts at t = 0)");
      increasing("cam.speed_table_t", c.speed_table_t);
    }

    // ---- contact
    const ContactSpec& k = s.contact;
    if (!k.separation && k.model != ContactModel::Lee && k.model != ContactModel::Holonomic)
      fail_at("contact.separation", "false",
              std::string("requires contact.model \"lee\" or \"holonomic\" (contact.model is \"") + to_string(k.model) +
                  "\")",
              "contact.model");
    if (k.restitution > 0 && (k.model == ContactModel::Penalty || k.model == ContactModel::Holonomic))
      fail_at("contact.restitution", fmt_num(k.restitution),
              std::string("must be 0 with contact.model \"") + to_string(k.model) +
                  "\" (restitution needs contact.model \"lee\" or \"event\")",
              "contact.model");

    // ---- solver
    const SolverSpec& v = s.solver;
    // IDA integrates the held contact as a DAE (src/engine/ida_engine.cpp): the constraint
    // u₀ = X_C(t) holds at all times, i.e. the holonomic model only.
    if (v.integrator == Integrator::Ida && k.model != ContactModel::Holonomic)
      fail_at("solver.integrator", "\"ida\"",
              std::string("\"ida\" requires contact.model = \"holonomic\" (contact.model is \"") +
                  to_string(k.model) + "\")",
              "contact.model");

    // ---- run
    if (!(s.run.output_dt <= s.run.t_end))
      fail_at("run.output_dt", fmt_num(s.run.output_dt), "must be <= run.t_end = " + fmt_num(s.run.t_end));

    network();
    criteria();
    camshaft();
  }

  // ---- [criteria], [lubricant], run.valve_node (rules between keys)
  void criteria() const {
    const Scene& s = s_;
    const CamSpec& c = s.cam;
    const CriteriaSpec& k = s.criteria;
    const LubricantSpec& l = s.lubricant;
    if (!s.run.valve_node.empty()) {
      if (s.follower.kind != FollowerKind::Network)
        fail_at("run.valve_node", quote(s.run.valve_node), "needs follower.kind = \"network\" (the valve is a node)",
                "follower.kind");
      bool found = false;
      for (const NodeSpec& n : s.network.nodes) found = found || n.name == s.run.valve_node;
      if (!found) fail_at("run.valve_node", quote(s.run.valve_node), "must name a node of [[nodes]]");
    }
    if (l.viscosity > 0) {
      if (!(c.width > 0))
        fail_at("lubricant.viscosity", fmt_num(l.viscosity),
                "the oil film needs the cam's width (cam.width > 0: the load per unit width)", "cam.width");
      if (c.follower_face != FollowerFace::Flat && c.follower_face != FollowerFace::Roller)
        fail_at("lubricant.viscosity", fmt_num(l.viscosity),
                "the oil film needs cam.follower_face = \"flat\" or \"roller\" (a line contact)", "cam.follower_face");
    }
    if (k.min_film_thickness > 0 && !(l.viscosity > 0))
      fail_at("criteria.min_film_thickness", fmt_num(k.min_film_thickness),
              "needs the oil film: lubricant.viscosity > 0", "lubricant.viscosity");
    if (k.min_lambda > 0 && !(l.viscosity > 0 && l.roughness > 0))
      fail_at("criteria.min_lambda", fmt_num(k.min_lambda),
              "needs the oil film and the roughness: lubricant.viscosity > 0 and lubricant.roughness > 0",
              "lubricant.roughness");
    if (k.max_hertz_stress > 0 && !(c.width > 0))
      fail_at("criteria.max_hertz_stress", fmt_num(k.max_hertz_stress), "needs the cam's width (cam.width > 0)",
              "cam.width");
    if (k.max_lift_deviation > 0 && s.run.valve_node.empty())
      fail_at("criteria.max_lift_deviation", fmt_num(k.max_lift_deviation),
              "needs the valve: run.valve_node naming a network node", "run.valve_node");
  }

  // ---- network (follower.kind = "network")

  /// The line of `key`, else of the nearest enclosing key recorded ("elements[2].nodes[1]"
  /// → "elements[2].nodes" → "elements[2]" → "elements").
  int net_line(std::string key) const {
    for (;;) {
      auto it = lines_.find(key);
      if (it != lines_.end()) return it->second;
      const auto cut = key.find_last_of(".[");
      if (cut == std::string::npos || cut == 0) return 0;
      key.resize(cut);
    }
  }
  /// A spring's coil-clash keys (free_length, solid_length, coil_gaps, coil_restitution).
  void coil_clash(const ElementSpec& e, const std::string& p, const std::string& who) const;
  /// A gas_load element's pressure table (each key's own rule is in its kind's table).
  void gas_load(const ElementSpec& e, const std::string& p, const std::string& who) const;
  [[noreturn]] void net_fail(const std::string& key, const std::string& value, const std::string& rule) const {
    throw SceneError(file_, net_line(key), key, value, rule);
  }
  void net_finite(const std::string& key, double v, const std::string& who) const {
    if (!std::isfinite(v)) net_fail(key, fmt_num(v), "must be a finite number (" + who + ")");
  }
  void net_ge(const std::string& key, double v, double lo, const std::string& who) const {
    net_finite(key, v, who);
    if (!(v >= lo)) net_fail(key, fmt_num(v), "must be >= " + fmt_num(lo) + " (" + who + ")");
    if (lo == 0.0 && v > 0.0 && v < 1.0 / kMaxMagnitude)
      net_fail(key, fmt_num(v),
               "is not a physical magnitude: must be 0 or >= " + fmt_num(1.0 / kMaxMagnitude) + " (" + who + ")");
  }
  void net_gt(const std::string& key, double v, double lo, const std::string& who) const {
    net_finite(key, v, who);
    if (!(v > lo)) net_fail(key, fmt_num(v), "must be > " + fmt_num(lo) + " (" + who + ")");
    // As the scalar keys: a positive magnitude below 1e-50 (a mass of 5e-324) is no physical
    // one; its reciprocal overflows (the mass matrix is then not positive definite).
    if (lo == 0.0 && v < 1.0 / kMaxMagnitude)
      net_fail(key, fmt_num(v),
               "is not a physical magnitude: must be >= " + fmt_num(1.0 / kMaxMagnitude) + " (" + who + ")");
  }
  static std::string quoted_names(const std::vector<std::string>& v) {
    std::vector<std::string> q;
    for (const auto& x : v) q.push_back(quote(x));
    return fmt_list(q);
  }
  static std::string element_label(const ElementSpec& e, std::size_t i) {
    return std::string(to_string(e.kind)) + (e.name.empty() ? " #" + std::to_string(i) : " '" + e.name + "'");
  }
  static std::string contact_label(const ContactPointSpec& c, std::size_t i) {
    return std::string(to_string(c.kind)) + " contact " + (c.name.empty() ? "#" + std::to_string(i) : "'" + c.name + "'");
  }
  static bool valid_node_name(const std::string& n) {
    for (char ch : n)
      if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-')) return false;
    return true;
  }

  void network() const;
  /// [camshaft] (src/scene/validate_camshaft.cpp).
  void camshaft() const;

 private:
  const Scene& s_;
  const std::string& file_;
  const LineMap& lines_;
};

}  // namespace scene_detail
}  // namespace camdyn
