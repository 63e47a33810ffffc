// camdyn — the verdict in words (issue 28; docs/contacts.md "The verdict"): what the
// follower does, per contact, classified from the cam's lift law at the event's angle.
//
//   CamRegions   the lobe of the cam (lift X − X_base over the cam's progress φ = dir·θ):
//                opening flank, nose, closing flank (the nose: the connected interval
//                around peak lift where the cam decelerates the follower, X″(φ) < 0).
//   make_verdict the departures of every contact from the run's events → VerdictItem list.
#pragma once

#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/summary.hpp"

namespace camdyn {
class MechanicalSystem;
namespace detail {

/// The regions of the cam's lobe, from its lift law X(θ) − X_base (sampled on a grid of
/// the cam's progress φ = dir·θ; dir = the sign of the cam's speed at t = 0).
class CamRegions {
 public:
  enum Region { Opening, Nose, Closing };
  CamRegions(const Cam& cam, const CamSpec& spec, int samples = 7200);
  /// The region of cam angle θ [rad].
  Region at(double theta) const;
  /// The lift above the base circle at θ [rad].
  double lift_at(double theta) const;
  double lift() const { return lift_; }
  /// Boundaries as cam angles in degrees [0, 360): lobe start, nose start, nose end, lobe end.
  double open_deg() const, nose_start_deg() const, nose_end_deg() const, close_deg() const;

 private:
  const Cam* cam_;
  double base_ = 0, lift_ = 0, dir_ = 1;
  double phi_open_ = 0;            // progress angle of the lobe start [rad]
  double o_n1_ = 0, o_n2_ = 0, o_c_ = 0;  // offsets from phi_open_ [rad], 0 ≤ n1 ≤ n2 ≤ c < 2π
  double deg_of_offset(double o) const;
};

/// The verdict's kind for a departure in region r ("opening_liftoff", "nose_float",
/// "closing_bounce").
const char* region_kind(CamRegions::Region r);
/// "lift-off on the opening flank", "float on the nose", "bounce on the closing flank",
/// "seat bounce", "no separation".
const char* kind_words(const std::string& kind);

/// The verdict of a finished (or stopped) run: `mech` null for a single follower (one cam
/// contact named "cam", no lash window: no seat holds it off the cam).
std::vector<VerdictItem> make_verdict(const Scene& scene, const MechanicalSystem* mech,
                                      const std::vector<ContactEvent>& events);
/// The one-liner: the items' texts joined by "; ".
std::string verdict_one_line(const std::vector<VerdictItem>& v);

}  // namespace detail
}  // namespace camdyn
