// camdyn — results of a run that an acceptance criterion judges (run_analysis.hpp).
#include "results/run_analysis.hpp"

#include <algorithm>
#include <cmath>

#include "camdyn/hertz.hpp"
#include "cam/follower_oscillating.hpp"
#include "results/designer_stats.hpp"  // angle_deg_mod360

namespace camdyn {
namespace detail {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kTakeUpBand = 0.01;  // the take-up band: 1 % of the cam's lift (contact_run.cpp)
}  // namespace

std::vector<std::string> RunAnalysis::columns(const Scene& sc) {
  std::vector<std::string> c;
  if (sc.lubricant.viscosity > 0) {
    c.push_back("film_thickness");
    if (sc.lubricant.roughness > 0) c.push_back("lambda");
  }
  if (!sc.run.valve_node.empty()) {
    if (!KinematicPath(sc).node(sc.run.valve_node).reached)
      throw SceneError(sc.source, 0, "run.valve_node", "\"" + sc.run.valve_node + "\"",
                       "is not reached from a cam contact through lash contacts, levers, bars and springs between "
                       "nodes (no kinematic lift)");
    c.push_back("lift_deviation");
  }
  return c;
}

RunAnalysis::RunAnalysis(const Scene& sc, const std::vector<std::string>& contacts,
                         const std::vector<std::string>& nodes, double lift, const Cam* cam)
    : sc_(sc), cam_(cam), path_(sc), timing_(sc, path_, nodes) {
  const CamSpec& c = sc.cam;
  band_ = kTakeUpBand * (lift > 0 ? lift : 0.0);
  if (sc.lubricant.viscosity > 0) {
    film_ = true;
    lambda_ = sc.lubricant.roughness > 0;
    oil_.viscosity = sc.lubricant.viscosity;
    oil_.pressure_viscosity = sc.lubricant.pressure_viscosity;
    oil_.composite_roughness = sc.lubricant.roughness;
    // E′ = 2 E* (Hamrock's effective modulus; hertz.hpp's contact_modulus is E*)
    Ep_ = effective_modulus(c.youngs_modulus, c.poisson_ratio, c.follower_youngs_modulus, c.follower_poisson_ratio);
    width_ = c.width;
    roller_ = c.follower_face == FollowerFace::Roller;
    rr_ = c.roller_radius;
    if (!roller_ && c.follower_motion == FollowerMotion::Oscillating) {
      pad_ = std::make_shared<const OscillatingGeometry>(c);
      pivot_x_ = c.pivot_x;
      pivot_y_ = c.pivot_y;
      auto cols = std::make_shared<const DesignerColumns>(sc);
      if (cols->pad_friction_on()) pad_friction_ = std::move(cols);
    }
  }
  if (!sc.run.valve_node.empty()) {
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes[i] == sc.run.valve_node) valve_ = int(i);
    valve_path_ = path_.node(sc.run.valve_node);
  }
  const double top = path_.take_up_levels().empty() ? 0.0 : path_.take_up_levels().back();
  // The seats: the network's stop contacts below their node (none without [[contacts]]).
  for (const ContactPointSpec& cp : sc.network.contacts) {
    if (!is_seat(cp)) continue;
    Seat s;
    s.name = cp.name;
    for (std::size_t j = 0; j < contacts.size(); ++j)
      if (contacts[j] == cp.name) s.contact = int(j);
    if (s.contact < 0) continue;
    const KinematicNode k = path_.node(cp.nodes[0]);
    s.opened_at = (k.reached ? k.take_up : top) + band_;
    seats_.push_back(std::move(s));
  }
  bool levels = false;
  for (double x : path_.take_up_levels()) levels = levels || x > 0;
  per_row_ = film_ || valve_ >= 0 || !seats_.empty() || levels || timing_.active();
}

double RunAnalysis::film(const CamPoint& p, double omega, double Fc) const {
  if (!(Fc > 0) || !std::isfinite(p.rho)) return NAN;
  const double N = pad_friction_ ? pad_friction_->normal_force(p, Fc, omega) : Fc * p.normal_force_ratio;
  const double curv = 1.0 / p.rho + (roller_ ? 1.0 / rr_ : 0.0);
  if (!(curv > 0)) return NAN;
  const double Rx = 1.0 / curv;
  return line_contact_min_film(N / width_, Rx, entrainment(p, omega), oil_, Ep_);
}

double RunAnalysis::entrainment(const CamPoint& p, double omega) const {
  if (pad_) return pad_entrainment(p.theta, omega);
  if (!roller_ || !cam_) return std::abs(flat_face_entrainment(omega, p.X_C, 0.0, p.d2X_dtheta2));
  // the contact point in the cam's frame, c(θ) = r (cos(β − θ), sin(β − θ)): its speed
  // over the cam's surface is the roller's rolling speed
  const double d = 1e-6;
  const CamPoint a = cam_->evaluate(p.theta - d), b = cam_->evaluate(p.theta + d);
  const double dx = b.r * std::cos(b.beta - b.theta) - a.r * std::cos(a.beta - a.theta);
  const double dy = b.r * std::sin(b.beta - b.theta) - a.r * std::sin(a.beta - a.theta);
  return std::abs(omega) * std::hypot(dx, dy) / (2 * d);
}

// The flat pad of an oscillating follower (a finger or rocker pad; the kinematics of
// cam/follower_oscillating.hpp). The pad is the line {Z : n(α)·(Z − P) = f} of the arm at
// angle α about the pivot P, u(α) = (cos α, sin α) along it; it touches the cam at Q(θ),
// which is on both surfaces: the common tangent is u(α). The surfaces' velocities relative
// to the contact point along u (the mean of which entrains the oil; Hamrock, Schmid,
// Jacobson, "Fundamentals of Machine Elements", §8.8: ũ = ½(u_a + u_b) with u_a, u_b the
// surface velocities relative to the conjunction) are minus the contact point's velocity
// over each surface:
//   over the pad: Q − P = e u + f n, so the point travels along the pad at ė = ω de/dθ,
//     e(θ) = u(α)·(Q − P);
//   over the cam: in the cam's frame (the cam turning counter-clockwise by θ) the point is
//     c(θ) = Rot(−θ) Q(θ) and travels at ω dc/dθ, in the fixed frame ω Rot(θ) dc/dθ, whose
//     component along u is ω (Rot(θ) dc/dθ)·u;
//   ũ = −½ ω (de/dθ + (Rot(θ) dc/dθ)·u).
// A translating flat face is the limit of a pivot at infinity (α fixed): then e = X_C′,
// de/dθ = X_C″ and (Rot(θ) dc/dθ)·u = X_C + X_C″, the −½ω(X_C + 2X_C″) of
// flat_face_entrainment (Norton, "Cam Design and Manufacturing Handbook", 2nd ed., ch. 13,
// derives that case the same way). Central differences δθ = 1e-6 of the exact kinematics.
double RunAnalysis::pad_entrainment(double theta, double omega) const {
  const double d = 1e-6;
  const OscillatingState a = pad_->eval(theta - d), b = pad_->eval(theta + d), m = pad_->eval(theta);
  auto e_of = [&](const OscillatingState& s) {
    return std::cos(s.alpha) * (s.f.cx - pivot_x_) + std::sin(s.alpha) * (s.f.cy - pivot_y_);
  };
  auto cam_frame = [](const OscillatingState& s, double th, double* x, double* y) {
    *x = std::cos(th) * s.f.cx + std::sin(th) * s.f.cy;
    *y = -std::sin(th) * s.f.cx + std::cos(th) * s.f.cy;
  };
  double ax, ay, bx, by;
  cam_frame(a, theta - d, &ax, &ay);
  cam_frame(b, theta + d, &bx, &by);
  const double dcx = (bx - ax) / (2 * d), dcy = (by - ay) / (2 * d);  // dc/dθ, cam frame
  // Rot(θ) dc/dθ · u(α) = dc/dθ · u(α − θ)
  const double along_cam = dcx * std::cos(m.alpha - theta) + dcy * std::sin(m.alpha - theta);
  const double de = (e_of(b) - e_of(a)) / (2 * d);
  return std::abs(0.5 * omega * (de + along_cam));
}

void RunAnalysis::row(double t, double theta, const CamPoint& p, double X, double Xdot, double omega, double Fc,
                      const std::vector<double>& gaps, const std::vector<double>& u, std::vector<double>& out) {
  if (std::isnan(theta0_)) theta0_ = theta;
  const double th_deg = angle_deg_mod360(theta);
  if (film_) {
    const double h = film(p, omega, Fc);
    out.push_back(h);
    if (lambda_) out.push_back(h / oil_.composite_roughness);
    if (!traced_ && !std::isnan(h) && (std::isnan(min_h_) || h < min_h_)) {
      min_h_ = h;
      min_h_theta_ = th_deg;
      min_lambda_ = lambda_ ? h / oil_.composite_roughness : NAN;
    }
  }
  if (valve_ >= 0) {
    const double d = u[std::size_t(valve_)] - valve_path_.lift(X);
    out.push_back(d);
    if (!traced_) keep_deviation(theta, d);
  }
  if (!traced_ && !std::isnan(prev_X_))
    for (double L : path_.take_up_levels()) {
      if (!(L > 0) || (prev_X_ - L) * (X - L) > 0 || prev_X_ == X) continue;
      const double w = (L - prev_X_) / (X - prev_X_);
      const double v = std::abs(prev_Xdot_ + w * (Xdot - prev_Xdot_));
      if (std::isnan(ramp_) || v > ramp_) {
        ramp_ = v;
        // the angle between the rows' angles (linear like the velocity)
        ramp_theta_ = angle_deg_mod360(prev_theta_ + w * (theta - prev_theta_));
      }
    }
  prev_X_ = X;
  prev_Xdot_ = Xdot;
  prev_theta_ = theta;
  if (timing_.active()) timing_.row(theta, u);
  for (Seat& s : seats_) {
    if (traced_) break;
    s.t.push_back(t);
    s.gap.push_back(gaps[std::size_t(s.contact)]);
    s.X.push_back(X);
  }
}

void RunAnalysis::keep_deviation(double theta, double d) {
  if (std::isnan(theta0_)) theta0_ = theta;
  const double th_deg = angle_deg_mod360(theta);
  // revolution k holds the progress (2πk, 2π(k + 1)] (the first also its start): a point at
  // a whole revolution closes the one it ends
  const long k = std::max(0L, long(std::ceil(std::abs(theta - theta0_) / kTwoPi - 1e-9)) - 1);
  LiftDeviationRevolution* r = nullptr;
  for (auto it = dev_.rbegin(); it != dev_.rend() && !r; ++it)
    if (it->revolution == k) r = &*it;
  if (!r) {
    dev_.push_back({k, d, th_deg, d, th_deg});
    std::sort(dev_.begin(), dev_.end(), [](const LiftDeviationRevolution& a, const LiftDeviationRevolution& b) {
      return a.revolution < b.revolution;
    });
    return;
  }
  if (d < r->min) r->min = d, r->min_theta_deg = th_deg;
  if (d > r->max) r->max = d, r->max_theta_deg = th_deg;
}

void RunAnalysis::step_inside(const std::vector<StepSample>& s, const StepProbe& probe) {
  traced_ = true;
  const int n = int(s.size());
  if (n < 2) return;
  const double t0 = s.front().t, h = s.back().t - t0;
  StepSample tmp;
  double x[kStepSamples], q[kStepSamples];
  for (int k = 0; k < n; ++k) x[k] = s[k].x;
  if (film_ && s[0].Fc > 0) {
    auto h_at = [&](const StepSample& p) { return film(p.cam_point(*cam_), p.omega, p.Fc); };
    for (int k = 0; k < n; ++k) q[k] = h_at(s[k]);
    const LocatedExtreme e = locate_extreme(x, q, n, -1, min_h_, [&](double xx) {
      probe(xx, tmp);
      return h_at(tmp);
    });
    if (e.found && (std::isnan(min_h_) || e.value < min_h_)) {
      min_h_ = e.value;
      probe(e.x, tmp);
      min_h_theta_ = angle_deg_mod360(tmp.theta);
      min_lambda_ = lambda_ ? e.value / oil_.composite_roughness : NAN;
    }
  }
  if (valve_ >= 0 && !s[0].nodes.empty()) {
    // the lift deviation's least and largest value in the step, each kept in the
    // revolution where it lies
    auto dev = [&](const StepSample& p) { return p.nodes[std::size_t(valve_)] - valve_path_.lift(p.X); };
    for (int k = 0; k < n; ++k) q[k] = dev(s[k]);
    for (int k = 0; k < n; ++k) keep_deviation(s[k].theta, q[k]);
    for (int sign : {-1, 1}) {
      const double rec = dev_.empty() ? NAN : sign < 0 ? dev_.back().min : dev_.back().max;
      const LocatedExtreme e = locate_extreme(x, q, n, sign, rec, [&](double xx) {
        probe(xx, tmp);
        return dev(tmp);
      });
      bool sample = false;
      for (int k = 0; k < n; ++k) sample = sample || e.x == x[k];
      if (!e.found || sample) continue;
      probe(e.x, tmp);
      keep_deviation(tmp.theta, e.value);
    }
  }
  // the ramp velocity: the cam's |Ẋ| where its lift X(t) crosses a take-up level inside the
  // step (the root of X − L on the step's cam motion, not between rows)
  for (double L : path_.take_up_levels()) {
    if (!(L > 0)) continue;
    for (int k = 0; k + 1 < n; ++k) {
      const double d0 = s[k].X - L, d1 = s[k + 1].X - L;
      if (d0 * d1 > 0.0 || d0 == d1) continue;
      const double sg = d0 > 0.0 || d1 < 0.0 ? 1.0 : -1.0;  // sg·(X − L) falls through zero
      const double xr = d0 == 0.0 ? x[k] : d1 == 0.0 ? x[k + 1]
                        : falling_root([&](double xx) { probe(xx, tmp); return sg * (tmp.X - L); },
                                       x[k], sg * d0, x[k + 1], sg * d1);
      probe(xr, tmp);
      const double v = std::abs(tmp.Xdot);
      if (std::isnan(ramp_) || v > ramp_) {
        ramp_ = v;
        ramp_theta_ = angle_deg_mod360(tmp.theta);
      }
    }
  }
  if (timing_.active()) timing_.step(s, probe);
  for (Seat& seat : seats_) {
    const std::size_t c = std::size_t(seat.contact);
    if (s[0].in_set[c]) continue;  // on its seat over the step
    double gmax = 0.0, Xmax = -INFINITY;
    for (int k = 0; k < n; ++k) {
      gmax = std::max(gmax, s[k].gaps[c]);
      Xmax = std::max(Xmax, s[k].X);
    }
    // the apex: the gap rate falls through zero between two samples
    for (int k = 0; k + 1 < n; ++k) {
      const double r0 = s[k].gap_rates[c], r1 = s[k + 1].gap_rates[c];
      if (!(r0 > 0.0 && r1 <= 0.0) || !(std::max(s[k].gaps[c], s[k + 1].gaps[c]) > 0.0)) continue;
      const double xa = falling_root(
          [&](double xx) {
            probe(xx, tmp);
            return tmp.gap_rates[c];
          },
          x[k], r0, x[k + 1], r1);
      probe(xa, tmp);
      gmax = std::max(gmax, tmp.gaps[c]);
    }
    if (!(gmax > 0.0) && !(Xmax > seat.opened_at)) continue;
    // one entry per run of steps between two impacts (strictly inside the step: after the
    // impact the step starts from, before one it ends on)
    if (!seat.t.empty() && seat.merged_impacts == seat.impacts.size()) {
      seat.gap.back() = std::max(seat.gap.back(), gmax);
      seat.X.back() = std::max(seat.X.back(), Xmax);
    } else {
      seat.t.push_back(t0 + 0.5 * h);
      seat.gap.push_back(gmax);
      seat.X.push_back(Xmax);
      seat.merged_impacts = seat.impacts.size();
    }
  }
}

void RunAnalysis::event(const ContactEvent& e, int j) {
  if (e.type != EventKind::Impact) return;
  for (Seat& s : seats_)
    if (s.contact == j) s.impacts.push_back(e);
}

void RunAnalysis::finish(Summary& s) const {
  s.min_film_thickness = min_h_;
  s.min_film_theta_deg = min_h_theta_;
  s.min_lambda = min_lambda_;
  s.lift_deviation = dev_;
  s.max_ramp_velocity = ramp_;
  s.max_ramp_theta_deg = ramp_theta_;
  s.valve_timing = timing_.results();
  for (const Seat& seat : seats_) {
    std::size_t r = 0;  // rows before the current impact: [.. r)
    double prev_t = -INFINITY;
    for (const ContactEvent& e : seat.impacts) {
      // rows strictly between the previous impact and this one
      double max_gap = 0.0, max_X = -INFINITY;
      while (r < seat.t.size() && seat.t[r] <= prev_t) ++r;
      for (std::size_t i = r; i < seat.t.size() && seat.t[i] < e.t; ++i) {
        max_gap = std::max(max_gap, seat.gap[i]);
        max_X = std::max(max_X, seat.X[i]);
      }
      const double th = angle_deg_mod360(e.theta);
      const bool bounce = std::isfinite(prev_t) && !(max_X > seat.opened_at) && !s.landings.empty() &&
                          s.landings.back().contact == seat.name;
      if (bounce) {
        SeatLanding& L = s.landings.back();
        ++L.bounces;
        if (max_gap > L.bounce_height) {
          L.bounce_height = max_gap;
          L.bounce_height_theta_deg = th;
        }
        if (e.impact_velocity > L.max_velocity) {
          L.max_velocity = e.impact_velocity;
          L.max_velocity_theta_deg = th;
        }
      } else {
        SeatLanding L;
        L.contact = seat.name;
        L.t = e.t;
        L.theta_deg = th;
        L.velocity = e.impact_velocity;
        L.max_velocity = e.impact_velocity;
        L.max_velocity_theta_deg = th;
        s.landings.push_back(L);
      }
      prev_t = e.t;
    }
  }
  std::stable_sort(s.landings.begin(), s.landings.end(),
                   [](const SeatLanding& a, const SeatLanding& b) { return a.t < b.t; });
}

}  // namespace detail
}  // namespace camdyn
