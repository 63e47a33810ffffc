// camdyn — designer results of one run (issue 15): force margin, event angles, largest
// impact velocity and gap, Poincaré samples and the period detector.
//
// Internal unit with a narrow API so that the step loops in simulator.cpp only report
// what they see (a force sample, an event, an accepted step end) and keep no designer
// logic of their own:
//   sample_force(t, θ, F)   a pointwise contact force while in contact
//   event(e)                an impact / separation (e.theta set)
//   step(t, θ, u, v, a, gap) an accepted step end (the first call is t = 0)
//   finish(summary)         writes the results into the Summary.
#pragma once

#include <memory>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/summary.hpp"
#include "results/designer_columns.hpp"
#include "results/step_extremes.hpp"

namespace camdyn {
namespace detail {

/// θ [rad] → degrees in [0, 360).
double angle_deg_mod360(double theta);

class DesignerStats {
 public:
  /// `lift`: the cam's lift (Cam::lift(), the period detector's length scale).
  DesignerStats(const Scene& scene, double lift);
  /// Also the cam-geometry results (issue 24): pressure angle, radius of curvature, side
  /// load, Hertz stress (cam.width > 0), cam torque T = F s′(θ) and power T ω.
  DesignerStats(const Scene& scene, const Cam& cam);
  /// The same on a shared cam (no copy). @pre cam is not null.
  DesignerStats(const Scene& scene, std::shared_ptr<const Cam> cam);

  /// A contact force sample F ≥ 0 at time t, cam angle θ, while in contact; `cp`: the cam
  /// at θ (Cam::evaluate(θ)) when the caller has it, else evaluated here.
  void sample_force(double t, double theta, double F, const CamPoint* cp = nullptr);
  /// An impact or separation event (type Impact/Separation; others ignored).
  void event(const ContactEvent& e);
  /// An accepted step end (state of the contact face). The first call is the start.
  void step(double t, double theta, double u, double v, double a, double gap);
  /// One accepted step (step_extremes.hpp: its kStepSamples samples and its interpolant):
  /// while the primary contact is held over it, the least force and the cam-geometry
  /// extremes (Hertz stress, side load, torque, power, friction force and power) located
  /// inside the step. The step ends' values come from here too (sample_force at a step end
  /// only adds the value after an event there).
  void step_inside(const std::vector<StepSample>& s, const StepProbe& probe);
  /// Fill the designer fields of `s`.
  void finish(Summary& s) const;

  /// The period detector on a sample sequence (exposed for tests): returns the smallest
  /// period p ≤ 16 with 2p + 1 ≤ samples.size() and every pair p apart within
  /// (tol·scale_u, tol·scale_v); 0 if none; kind set as Summary::period_kind.
  static int detect_period(const std::vector<PoincareSample>& samples, double scale_u,
                           double scale_v, double tol, std::string* kind);

 private:
  CamDrive drive_;
  double lift_ = 1.0;
  double theta0_ = 0, dir_ = 1, phi_s_ = 0;  // section: progress φ = dir (θ − θ₀) = φ_s + 2πk
  long settle_ = 0;
  long next_k_ = 0;  // the next revolution to sample
  double tol_ = 1e-3;
  double max_omega_ = 0;
  bool have_prev_ = false;
  double t0_ = 0, th0_ = 0, u0_ = 0, v0_ = 0, a0_ = 0;
  // results
  double min_F_ = NAN, min_F_theta_ = NAN;
  double first_sep_ = NAN, first_imp_ = NAN;
  double max_vimp_ = 0, max_vimp_theta_ = NAN;
  double max_gap_ = 0;
  std::vector<PoincareSample> poincare_;
  // cam geometry (issue 24; designer_geometry.cpp)
  std::shared_ptr<const Cam> cam_;
  std::shared_ptr<const DesignerColumns> cols_;
  double geo_max_phi_ = NAN, geo_min_rho_ = NAN;
  double max_side_ = NAN, max_hertz_ = NAN, max_hertz_theta_ = NAN;
  double T_peak_ = NAN, P_peak_ = NAN, T_int_ = 0, P_int_ = 0, t_first_ = NAN;
  double pend_t0_ = NAN, pend_T0_ = 0, pend_P0_ = 0, pend_t1_ = NAN, pend_T1_ = 0, pend_P1_ = 0;
  // cam friction (cols_->friction()): torque and power integrals as T, P above
  double Tf_int_ = 0, Pf_int_ = 0, pend_Tf0_ = 0, pend_Pf0_ = 0, pend_Tf1_ = 0, pend_Pf1_ = 0;
  double Ff_max_ = NAN, Pf_peak_ = NAN;
  void geometry_init(const Scene& scene, std::shared_ptr<const Cam> cam);
  void geometry_sample(double t, double theta, double F, const CamPoint* cp);
  void geometry_step(double t);
  void geometry_finish(Summary& s) const;
  // the force-dependent extremes at one (θ, F, ω): the record keeping of sample_force and
  // step_inside
  struct Design {
    double hertz = NAN, side = NAN, torque = NAN, power = NAN, friction = NAN, friction_power = NAN;
  };
  Design design_at(double theta, double F, double omega) const;
  Design design_at(const CamPoint& cp, double F, double omega) const;
  void keep_extremes(double theta, const Design& d);
};

}  // namespace detail
}  // namespace camdyn
