// camdyn — the start of a run (include/camdyn/initial_state.hpp, src/run/initial_check.hpp):
// the cam's base X, the lift a network's gap sees, the check of the initial gaps (one
// place for every follower kind and contact method: Simulator's constructors), and the
// helper that puts a user follower on the cam.
#include "camdyn/initial_state.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "contact/laws/contact_law.hpp"
#include "run/initial_check.hpp"
#include "mechanism/mechanism.hpp"
#include "cam/format.hpp"  // detail::fmt
#include "scene/shared_cam.hpp"

namespace camdyn {

CamMotion cam_lift_motion(const CamSpec& spec, double t) {
  const std::shared_ptr<const Cam> cam_owner = detail::shared_cam(spec);
  const Cam& cam = *cam_owner;
  const CamDrive drive(spec);
  CamMotion m = cam.motion(drive.theta(t), drive.omega(t), drive.omega_dot(t));
  m.X -= cam_lift_base(cam, spec);
  return m;
}

FollowerStart initial_state_on_cam(const Scene& scene, const FollowerSystem& follower) {
  auto fail = [](const std::string& key, const std::string& value, const std::string& rule) {
    throw SceneError("<follower>", 0, key, value, rule);
  };
  const int n = follower.size();
  if (n < 1) fail("size()", std::to_string(n), "must be >= 1");
  const std::vector<FollowerContact> cs = follower.contacts();
  const int m = int(cs.size());
  FollowerStart s;
  s.q.assign(std::size_t(n), 0.0);
  s.v.assign(std::size_t(n), 0.0);
  follower.initial_state(s.q.data(), s.v.data());
  const CamMotion cm = cam_lift_motion(scene.cam, 0.0);
  Eigen::MatrixXd T(m, n), MTt(n, m);
  Eigen::VectorXd rq(m), rv(m);
  Eigen::Map<Eigen::VectorXd> q(s.q.data(), n), v(s.v.data(), n);
  bool any_cam = false;
  for (int j = 0; j < m; ++j) {
    if (int(cs[j].row.size()) != n)
      fail("contacts()[" + std::to_string(j) + "].row", std::to_string(cs[j].row.size()) + " entries",
           "must have size() = " + std::to_string(n) + " entries");
    T.row(j) = Eigen::Map<const Eigen::RowVectorXd>(cs[j].row.data(), n);
    const Eigen::VectorXd b = T.row(j).transpose();
    follower.solve_mass(b.data(), MTt.col(j).data());
    // cam contacts: close them (gap and rate to 0); the others: keep their gap and rate
    rq[j] = cs[j].cam ? -(T.row(j).dot(q) + cs[j].clearance - cm.X) : 0.0;
    rv[j] = cs[j].cam ? -(T.row(j).dot(v) - cm.Xdot) : 0.0;
    any_cam |= cs[j].cam;
  }
  if (!any_cam) fail("contacts()", std::to_string(m) + " contacts", "has no cam contact (cam = true) to put on the cam");
  const Eigen::MatrixXd W = T * MTt;
  const auto dec = W.completeOrthogonalDecomposition();
  q += MTt * dec.solve(rq);
  v += MTt * dec.solve(rv);
  return s;
}

namespace detail {
namespace {

// "G < bound" of the message: −contact.tol_u, or the penalty method's −(s + tol_u).
std::string below(const Scene& sc, double gap, double depth) {
  const double tol = sc.contact.tol_u;
  if (sc.contact.model != ContactModel::Penalty) return fmt(gap) + " < -contact.tol_u = " + fmt(-tol);
  return fmt(gap) + " < -(its penalty equilibrium penetration " + fmt(depth) + " + contact.tol_u " + fmt(tol) +
         ") = " + fmt(-(depth + tol));
}

// "a, b and c"
std::string join_and(const std::vector<std::string>& v) {
  std::string r;
  for (std::size_t i = 0; i < v.size(); ++i) r += (i == 0 ? "" : i + 1 == v.size() ? " and " : ", ") + v[i];
  return r;
}

std::string rule(const std::string& contact, const std::string& bound, const std::vector<std::string>& terms) {
  return "the start penetrates contact '" + contact + "': its gap at t = 0 is " + bound + ", set by " +
         join_and(terms) + "; a run starts on the contact (gap 0) or off it";
}

}  // namespace

void check_start(const Scene& sc, const MechanicalSystem& mech, StartKeys keys) {
  const bool user = keys == StartKeys::User;
  // A cam_lift_absolute mechanism's gap (a rigid or elastic_bar follower's) sees the cam's
  // X_C itself (u_c = q₀).
  const bool absolute = mech.traits().cam_lift_absolute;
  const int n = mech.n(), m = mech.m();
  const std::shared_ptr<const Cam> cam_owner = detail::shared_cam(sc.cam);
  const Cam& cam = *cam_owner;
  const CamDrive drive(sc.cam);
  const double base = !absolute && mech.cam_contacts() > 0 ? cam_lift_base(cam, sc.cam) : 0.0;
  const CamMotion cm = cam.motion(drive.theta(0.0), drive.omega(0.0), drive.omega_dot(0.0));
  const Eigen::VectorXd& q = mech.q0();
  Eigen::VectorXd a0(n);
  bool have_a0 = false;
  for (int j = 0; j < m; ++j) {
    const MechanismContact& c = mech.contacts()[j];
    const CamShaft* shaft = mech.camshaft();
    const bool on_shaft = shaft && shaft->contact_cam(j) >= 0;  // the cam at its station's angle
    const double lift = on_shaft ? shaft->lift(j, 0.0, q.data()).X : c.cam ? cm.X - base : 0.0;
    const double gap = c.t.dot(q) + c.g0 - lift;
    if (gap >= -sc.contact.tol_u) continue;
    double depth = 0.0;
    if (sc.contact.model == ContactModel::Penalty) {
      if (!have_a0) {
        mech.acceleration(0.0, q.data(), mech.v0().data(), Eigen::VectorXd::Zero(m), a0.data(), false,
                         mech.states() ? mech.s0().data() : nullptr);
        have_a0 = true;
      }
      const double Xdd =
          on_shaft ? shaft->contact_cam_motion(j, 0.0, q.data(), mech.v0().data()).Xddot : c.cam ? cm.Xddot : 0.0;
      const double F = (Xdd - c.t.dot(a0)) / mech.W()(j, j);
      depth = c.law.penalty.depth_at(F);
      if (gap >= -(depth + sc.contact.tol_u)) continue;
    }
    // The keys that set this gap.
    std::string file, key, value;
    std::vector<std::string> terms;
    if (absolute) {
      file = sc.source;
      key = "contact.initial_gap";
      value = fmt(sc.contact.initial_gap);
      terms.push_back("the follower's face q(0) = " + fmt(q[0]));
      terms.push_back("the cam's X_C(0) = " + fmt(cm.X) + " (absolute)");
    } else if (user) {
      file = "<follower>";
      key = "initial_state()";
      std::string qs;
      for (int i = 0; i < n && i < 6; ++i) qs += (i ? ", " : "") + fmt(q[i]);
      value = "q0 = [" + qs + (n > 6 ? ", …" : "") + "]";
      terms.push_back("row · q0 = " + fmt(c.t.dot(q)) + " from initial_state()");
      terms.push_back("contacts()[" + std::to_string(j) + "].clearance = " + fmt(c.g0));
    } else {
      file = sc.source;
      const ContactPointSpec& cs = sc.network.contacts.at(std::size_t(j));
      const auto& nodes = sc.network.nodes;
      for (const std::string& name : cs.nodes) {
        const auto it = std::find_if(nodes.begin(), nodes.end(), [&](const NodeSpec& nd) { return nd.name == name; });
        if (it == nodes.end()) continue;
        const std::string nk = "nodes[" + std::to_string(it - nodes.begin()) + "].initial_displacement";
        if (key.empty()) {
          key = nk;
          value = fmt(it->initial_displacement);
        }
        terms.push_back(nk + " = " + fmt(it->initial_displacement) + " (node '" + it->name + "')");
      }
      terms.push_back("contacts[" + std::to_string(j) + "].clearance = " + fmt(c.g0));
    }
    if (c.cam && !absolute)
      terms.push_back("the cam's lift X_C(0) - X_base = " + fmt(lift) + " (X_C(0) = " + fmt(cm.X) + ", X_base = " +
                      fmt(base) + ": " +
                      (sc.cam.profile == CamProfileKind::Lift ? "cam.base_radius" : "the smallest X_C over a revolution") +
                      ")");
    std::string r = rule(c.name, below(sc, gap, depth), terms);
    if (user && c.cam) r += " (initial_state_on_cam(), C++ and Python, gives a state on the cam)";
    throw SceneError(file, 0, key, value, r);
  }
}

}  // namespace detail
}  // namespace camdyn
