// camdyn — the verdict in words (see verdict.hpp; docs/contacts.md "The verdict").
#include "results/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "cam/lift_base.hpp"
#include "results/designer_stats.hpp"  // angle_deg_mod360
#include "mechanism/mechanism.hpp"
#include "scene/shared_cam.hpp"

namespace camdyn {
namespace detail {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kFloatLift = 0.01;  // a departure counts with the cam 1 % of its lift above the lash

double wrap(double x) {
  double r = std::fmod(x, kTwoPi);
  if (r < 0) r += kTwoPi;
  if (r >= kTwoPi) r = 0.0;
  return r;
}

std::string num_text(const char* f, double x) {
  char b[64];
  std::snprintf(b, sizeof b, f, x);
  return b;
}
}  // namespace

CamRegions::CamRegions(const Cam& cam, const CamSpec& spec, int samples) : cam_(&cam) {
  base_ = cam_lift_base(cam, spec);
  lift_ = cam.lift();
  const CamDrive drive(spec);
  dir_ = drive.omega(0.0) < 0 ? -1.0 : 1.0;
  const int n = std::max(samples, 360);
  const double d = kTwoPi / n;
  std::vector<double> X(n), X2(n);
  double x2max = 0;
  for (int k = 0; k < n; ++k) {
    const CamMotion m = cam.motion(dir_ * d * k, 1.0, 0.0);
    X[k] = m.X;
    X2[k] = m.Xddot;  // d²X/dφ² = d²X/dθ² (φ = dir θ)
    x2max = std::max(x2max, std::abs(m.Xddot));
  }
  const int kp = int(std::max_element(X.begin(), X.end()) - X.begin());
  const double xmin = *std::min_element(X.begin(), X.end());
  const double eps = 1e-6 * std::max(lift_, 1e-300), thr = 1e-9 * x2max;
  auto prev = [n](int k) { return (k + n - 1) % n; };
  auto next = [n](int k) { return (k + 1) % n; };
  // The lobe: back and forth from the peak to the base circle.
  int ko = kp, kc = kp;
  for (int i = 0; i < n && X[ko] > xmin + eps; ++i) ko = prev(ko);
  for (int i = 0; i < n && X[kc] > xmin + eps; ++i) kc = next(kc);
  // The nose: the connected run of X″ ≤ 0 (to round-off) around the peak, inside the lobe.
  int n1 = kp, n2 = kp;
  while (n1 != ko && X2[prev(n1)] <= thr) n1 = prev(n1);
  while (n2 != kc && X2[next(n2)] <= thr) n2 = next(n2);
  phi_open_ = d * ko;
  auto off = [&](int k) { return wrap(d * k - phi_open_); };
  o_n1_ = off(n1);
  o_n2_ = std::max(o_n1_, off(n2));
  o_c_ = std::max(o_n2_, off(kc));
  if (kc == ko) o_c_ = std::max(o_n2_, kTwoPi - d);  // no base circle (an eccentric)
}

CamRegions::Region CamRegions::at(double theta) const {
  const double o = wrap(dir_ * theta - phi_open_);
  if (o < o_n1_) return Opening;
  if (o <= o_n2_) return Nose;
  if (o <= o_c_) return Closing;
  // on the base circle: its first half follows the closing flank, its second precedes the opening
  return o - o_c_ < 0.5 * (kTwoPi - o_c_) ? Closing : Opening;
}

double CamRegions::lift_at(double theta) const { return cam_->motion(theta, 1.0, 0.0).X - base_; }

double CamRegions::deg_of_offset(double o) const { return angle_deg_mod360(dir_ * (phi_open_ + o)); }
double CamRegions::open_deg() const { return deg_of_offset(0.0); }
double CamRegions::nose_start_deg() const { return deg_of_offset(o_n1_); }
double CamRegions::nose_end_deg() const { return deg_of_offset(o_n2_); }
double CamRegions::close_deg() const { return deg_of_offset(o_c_); }

const char* region_kind(CamRegions::Region r) {
  switch (r) {
    case CamRegions::Opening: return "opening_liftoff";
    case CamRegions::Nose: return "nose_float";
    case CamRegions::Closing: return "closing_bounce";
  }
  return "";
}

const char* kind_words(const std::string& kind) {
  if (kind == "opening_liftoff") return "lift-off on the opening flank";
  if (kind == "nose_float") return "float on the nose";
  if (kind == "closing_bounce") return "bounce on the closing flank";
  if (kind == "seat_bounce") return "seat bounce";
  return "no separation";
}

std::vector<VerdictItem> make_verdict(const Scene& sc, const MechanicalSystem* mech,
                                      const std::vector<ContactEvent>& events) {
  enum Role { RCam, RLash, RStop };
  struct C {
    std::string name;
    Role role;
    double clearance;
  };
  const std::shared_ptr<const Cam> cam_owner = detail::shared_cam(sc.cam);
  const Cam& cam = *cam_owner;
  const CamRegions reg(cam, sc.cam);
  const CamDrive drive(sc.cam);
  std::vector<C> cs;
  if (mech) {
    for (const MechanismContact& c : mech->contacts()) {
      if (!c.coil_spring.empty()) continue;  // coil clash is reported on its own (summary coil_clash)
      Role r = RLash;
      if (c.cam) r = RCam;
      else if (c.kind == ContactPointKind::Stop) r = RStop;
      else if (c.kind == ContactPointKind::Cam)  // a user follower's non-cam row: one entry → a stop
        r = (c.t.array() != 0.0).count() == 1 ? RStop : RLash;
      cs.push_back({c.name, r, c.g0});
    }
  } else {
    // a single follower has no seat: its spring keeps it on the cam, and an initial gap
    // closes once at the start (an impact), so no lash window
    cs.push_back({"cam", RCam, 0.0});
  }
  // The chain's lash: a separation of a cam or lash contact with the cam lifted less than
  // this (plus kFloatLift of the lift) is the lash opening by design, not a phenomenon.
  double lash = 0;
  for (const C& c : cs)
    if (c.role != RStop) lash += c.clearance;
  const double lift = reg.lift();

  struct Item {
    VerdictItem v;
    double t;
  };
  std::map<std::pair<std::string, std::string>, Item> items;
  auto add = [&](const std::string& kind, int j, const ContactEvent& e) {
    auto key = std::make_pair(kind, cs[size_t(j)].name);
    auto it = items.find(key);
    if (it == items.end()) {
      Item x;
      x.v.kind = kind;
      x.v.contact = cs[size_t(j)].name;
      x.v.theta_deg = angle_deg_mod360(e.theta);
      x.v.speed_rev_s = drive.omega(e.t) / kTwoPi;
      x.t = e.t;
      it = items.emplace(key, x).first;
    }
    ++it->second.v.count;
  };
  enum Last { None, Imp, Sep };
  std::vector<Last> last(cs.size(), None);
  std::vector<ContactEvent> last_impact(cs.size());
  std::vector<char> opened_by_cam(cs.size(), 0);
  for (const ContactEvent& e : events) {
    if (e.type != EventKind::Impact && e.type != EventKind::Separation) continue;
    int j = 0;
    if (mech) {
      j = -1;
      for (size_t i = 0; i < cs.size(); ++i)
        if (cs[i].name == e.contact) j = int(i);
      if (j < 0) continue;
    }
    const C& c = cs[size_t(j)];
    if (e.type == EventKind::Impact) {
      if (c.role == RStop) {
        // a stop that bounced off (no hold), or was left while the cam was not opening it
        if (last[j] == Imp || (last[j] == Sep && !opened_by_cam[j])) add("seat_bounce", j, e);
      } else if (last[j] == Imp) {
        // the previous impact left the contact open (restitution): a bounce there
        const ContactEvent& b = last_impact[j];
        add(region_kind(reg.at(b.theta)), j, b);
      }
      last[j] = Imp;
      last_impact[j] = e;
    } else {
      if (c.role == RStop) {
        opened_by_cam[j] = reg.at(e.theta) == CamRegions::Opening && reg.lift_at(e.theta) > 0.0;
      } else if (reg.lift_at(e.theta) > lash + kFloatLift * lift) {
        add(region_kind(reg.at(e.theta)), j, e);
      }
      last[j] = Sep;
    }
  }
  std::vector<Item> sorted;
  for (auto& kv : items) sorted.push_back(kv.second);
  std::stable_sort(sorted.begin(), sorted.end(), [](const Item& a, const Item& b) { return a.t < b.t; });
  std::vector<VerdictItem> out;
  for (Item& x : sorted) {
    VerdictItem& v = x.v;
    v.text = std::string(kind_words(v.kind)) + ": contact '" + v.contact + "' at " +
             num_text("%.1f", v.theta_deg) + " deg, " + num_text("%.6g", v.speed_rev_s) + " rev/s" +
             (v.count > 1 ? " (" + std::to_string(v.count) + " times)" : "");
    out.push_back(v);
  }
  if (out.empty()) {
    VerdictItem v;
    v.kind = "no_separation";
    v.text = kind_words(v.kind);
    out.push_back(v);
  }
  return out;
}

std::string verdict_one_line(const std::vector<VerdictItem>& v) {
  std::string s;
  for (const VerdictItem& x : v) s += (s.empty() ? "" : "; ") + x.text;
  return s;
}

}  // namespace detail
}  // namespace camdyn
