// camdyn (private) — the C0 joints of a motion law (issue 24): the cam angles where the
// follower's velocity s′(θ) jumps (a constant-velocity ramp next to a dwell or a rise).
//
//   A follower held on the cam is struck there: the cam's velocity Ẋ_C jumps by
//   Δs′·ω in no time, a velocity-level jump that only an impulse can follow. The methods
//   land their steps on the joints (cam_stops.hpp) and resolve the jump there as an
//   impact of the cam on the follower (ContactRun::cam_joint_impact): the step that ends
//   on the joint sees the cam's motion before it (the left limit, in the drive's
//   direction), the steps after it the motion after it (the right limit). The one-sided
//   limits are evaluated η = 1e-7 rad inside the segment and corrected to first order
//   (s′ ± η s″, s″ ± η s‴: an error η² s‴/2, ~1e-14 of the lift per rad²).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/cam_spec.hpp"

namespace camdyn {
namespace detail {

/// The cam's motion at t one-sided at a breakpoint: when θ(t) is within 1e-9 rad of one of
/// `angles` (mod 2π): true, and `m` the motion at t of the segment just before (side < 0)
/// or just after (side > 0) the breakpoint in the drive's direction — that segment's
/// derivatives, evaluated η = 1e-7 rad inside it and carried to θ(t) to first order
/// (X′ + Δ X″, X″ + Δ X‴, Δ = θ(t) − the point inside: an error η² X⁗/2). X_C itself is
/// continuous and evaluated at θ(t). false: no breakpoint there (m untouched).
inline bool one_sided_motion(const Cam& cam, const CamDrive& drive, const std::vector<double>& angles, double t,
                             int side, CamMotion* m) {
  constexpr double kTwoPi = 6.283185307179586476925286766559, eta = 1e-7;
  const double th = drive.theta(t);
  for (double a : angles) {
    const double d = std::remainder(th - a, kTwoPi);
    if (!(std::abs(d) <= 1e-9 * std::max(1.0, std::abs(th)))) continue;
    const double w = drive.omega(t), wd = drive.omega_dot(t);
    const double s = (w >= 0 ? 1.0 : -1.0) * (side > 0 ? 1.0 : -1.0);  // the side in θ
    const CamPoint p = cam.evaluate(th - d + s * eta);
    const double D = d - s * eta;  // θ(t) − the point inside
    const double X1 = p.dX_dtheta + D * p.d2X_dtheta2;
    const double X2 = p.d2X_dtheta2 + D * p.d3X_dtheta3;
    m->X = cam.evaluate(th).X_C;
    m->Xdot = X1 * w;
    m->Xddot = X2 * w * w + X1 * wd;
    return true;
  }
  return false;
}

class CamJoints {
 public:
  CamJoints(const CamSpec& spec, const Cam& cam) : drive_(spec) {
    if (spec.land_on_breaks)
      for (const Breakpoint& b : cam.joints())
        if (b.order == 0) angles_.push_back(b.theta);
  }
  bool empty() const { return angles_.empty(); }
  /// When θ(t) is on a C0 joint (within 1e-9 rad): true, and `m` the cam's motion at t
  /// just before (side < 0) or just after (side > 0) the joint in the drive's direction.
  bool at(const Cam& cam, double t, int side, CamMotion* m) const {
    return one_sided_motion(cam, drive_, angles_, t, side, m);
  }

 private:
  CamDrive drive_;
  std::vector<double> angles_;
};

}  // namespace detail
}  // namespace camdyn
