// camdyn — the absolute tolerances a contact run gives its engine: solver.atol, raised to
// the round-off floor of the positions and velocities where it is below it.
//
// The cam's motion is computed to a few ε of its scale (the contact point of a spline or an
// arc cam is found by an iteration; case A7's Ẋ_C scatters by 4e-14 around its exact value
// near θ = 0, 6ε of its 30 length/s scale), and a held contact puts the follower on it. An
// error test weighted by an atol below that scatter cannot pass at any step size: CVODE,
// whose projection carries the scatter into its history, took steps of 1e-18 s (case A7 at
// rtol 1e-10, atol 1e-14; the arc cam example at atol 1e-12 in millimetres). The floor is
// kAtolRoundoff·ε times the scale: positions max|X_C| over a turn, velocities that times the
// largest cam speed (and the shaft stations' speeds); the elements' states keep solver.atol.
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact_run.hpp"
#include "mechanism/camshaft.hpp"

namespace camdyn {
namespace detail {

namespace {
constexpr double kAtolRoundoff = 100.0;
}  // namespace

Eigen::VectorXd ContactRun::absolute_tolerances() {
  const double atol = sc_.solver.atol, eps = std::numeric_limits<double>::epsilon();
  const CamScales scale = cam_scales(cam_);
  const double X = scale.X, dX = scale.dX;
  double rev_s = std::abs(sc_.cam.speed_rev_s);
  for (double w : sc_.cam.speed_table_rev_s) rev_s = std::max(rev_s, std::abs(w));
  double fluct = 1.0;  // a camshaft's crank orders: θ̇ up to ω(1 + Σ n_k a_k)
  const CamshaftSpec& cs = sc_.camshaft;
  for (std::size_t k = 0; k < cs.crank_orders.size() && k < cs.crank_amplitudes_deg.size(); ++k)
    fluct += std::abs(cs.crank_orders[k] * cs.crank_amplitudes_deg[k]) * M_PI / 180.0;
  const double omega = 2.0 * M_PI * rev_s * fluct;
  const double floor_q = kAtolRoundoff * eps * X, floor_v = kAtolRoundoff * eps * dX * omega;
  const double floor_w = kAtolRoundoff * eps * omega;  // a shaft station's speed
  const bool shaft = mk_.camshaft() != nullptr;
  if (atol >= floor_q && atol >= floor_v && (!shaft || atol >= floor_w)) return {};
  Eigen::VectorXd a = Eigen::VectorXd::Constant(ny_, atol);
  a.head(n_).setConstant(std::max(atol, floor_q));
  a.segment(n_, n_).setConstant(std::max(atol, floor_v));
  if (const CamShaft* c = mk_.camshaft())
    for (int i = 0; i < c->stations(); ++i)
      if (const int d = c->station_dof(i); d >= 0) {
        a[d] = atol;  // an angle: rtol·|φ| bounds its round-off
        a[n_ + d] = std::max(atol, floor_w);
      }
  atol_note_ = "solver.atol = " + fmt(atol) + " is below the round-off floor of the follower's " +
               (atol < floor_v ? "velocities (" + fmt(floor_v) + ")" : "positions (" + fmt(floor_q) + ")") +
               ", " + fmt(kAtolRoundoff) + "·ε times their scale over a turn of the cam: the floor was used there";
  return a;
}

}  // namespace detail
}  // namespace camdyn
