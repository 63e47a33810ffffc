// camdyn — the hydraulic lash adjuster (hydraulic_lash_adjuster.hpp has the model).
#include "mechanism/elements/hydraulic_lash_adjuster.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "camdyn/network.hpp"
#include "scene/key_table.hpp"  // format_number

namespace camdyn {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kMinVolume = 0.01;       // V(δ) ≥ this × chamber_volume
constexpr double kMinAbsPressure = 1e-3;  // p_abs ≥ this × p_ref inside β_eff
}  // namespace

HydraulicLashAdjuster::HydraulicLashAdjuster(const ElementSpec& s, std::string name)
    : Element(std::move(name), 2, s.check_ball_mass > 0.0 ? 5 : 3),
      A_(s.area),
      V0_(s.chamber_volume),
      beta_(s.bulk_modulus),
      alpha_(s.air_fraction),
      p_ref_(s.air_reference_pressure),
      leak_(kPi * s.plunger_diameter * s.leak_clearance * s.leak_clearance * s.leak_clearance /
            (12.0 * s.viscosity * s.leak_length)),
      p_s_(s.supply_pressure),
      dp_open_(s.check_opening_pressure),
      check_c_(s.check_discharge_coefficient * s.check_area * std::sqrt(2.0 / s.oil_density)),
      dp_t_(s.check_transition_pressure),
      k_(s.stiffness),
      P_(s.preload),
      p0_(s.initial_pressure),
      p_abs_min_(kMinAbsPressure * s.air_reference_pressure),
      mb_(s.check_ball_mass),
      kb_(s.check_ball_stiffness),
      cb_(s.check_ball_damping),
      As_(0.25 * kPi * s.check_seat_diameter * s.check_seat_diameter),
      Pb_(s.check_opening_pressure * As_),
      ks_(s.check_seat_stiffness),
      ball_c_(s.check_discharge_coefficient * kPi * s.check_seat_diameter * std::sqrt(2.0 / s.oil_density)),
      x_open_(s.check_seat_diameter > 0.0 ? (s.check_area > 0.0 ? s.check_area : As_) / (kPi * s.check_seat_diameter)
                                          : 0.0),
      nodes_(s.nodes) {}

std::string HydraulicLashAdjuster::describe() const {
  using detail::format_number;
  std::ostringstream d;
  d << "hydraulic_lash_adjuster '" << name() << "' [" << nodes_.at(0) << " → " << nodes_.at(1) << "] A "
    << format_number(A_) << ", V0 " << format_number(V0_) << ", beta " << format_number(beta_) << ", air "
    << format_number(alpha_) << ", leak " << format_number(leak_) << " per pressure, supply " << format_number(p_s_)
    << ", stiffness at p(0) " << format_number(bulk_modulus(p0_) * A_ * A_ / V0_);
  if (has_ball())
    d << ", check ball " << format_number(mb_) << " on k " << format_number(kb_) << " opening at "
      << format_number(dp_open_) << ", full open at lift " << format_number(x_open_) << ", on its seat "
      << format_number(std::sqrt(ks_ / mb_)) << " rad/s";
  return d.str();
}

double HydraulicLashAdjuster::chamber_volume(double delta) const {
  return std::max(V0_ - A_ * delta, kMinVolume * V0_);
}

double HydraulicLashAdjuster::bulk_modulus(double p) const {
  if (alpha_ == 0.0) return beta_;
  const double pa = std::max(p_ref_ + p, p_abs_min_);
  const double vl = 1.0 - alpha_, vg = alpha_ * p_ref_ / pa;
  return (vl + vg) / (vl / beta_ + vg / pa);
}

double HydraulicLashAdjuster::dbulk_dp(double p) const {
  if (alpha_ == 0.0 || p_ref_ + p <= p_abs_min_) return 0.0;
  const double pa = p_ref_ + p;
  const double vl = 1.0 - alpha_, b = alpha_ * p_ref_;
  const double N = vl + b / pa, D = vl / beta_ + b / (pa * pa);
  const double dN = -b / (pa * pa), dD = -2.0 * b / (pa * pa * pa);
  return (dN * D - N * dD) / (D * D);
}

double HydraulicLashAdjuster::check_flow(double p) const {
  const double d = p_s_ - p - dp_open_;
  if (!(d > 0.0) || check_c_ == 0.0) return 0.0;
  return check_c_ * d / std::pow(d * d + dp_t_ * dp_t_, 0.25);
}

double HydraulicLashAdjuster::dcheck_dp(double p) const {
  const double d = p_s_ - p - dp_open_;
  if (!(d > 0.0) || check_c_ == 0.0) return 0.0;
  const double r = d * d + dp_t_ * dp_t_;
  return -check_c_ * (0.5 * d * d + dp_t_ * dp_t_) / std::pow(r, 1.25);  // dΔ/dp = −1
}

double HydraulicLashAdjuster::ball_flow(double p, double x) const {
  if (!has_ball() || !(x > 0.0)) return 0.0;
  const double d = p_s_ - p;
  return ball_c_ * std::min(x, x_open_) * d / std::pow(d * d + dp_t_ * dp_t_, 0.25);
}

double HydraulicLashAdjuster::ball_acceleration(double p, double x, double w) const {
  const double seat = x < 0.0 ? -ks_ * x : 0.0;
  return ((p_s_ - p) * As_ - Pb_ - kb_ * x - cb_ * w + seat) / mb_;
}

double HydraulicLashAdjuster::inflow(const ElementState& e, double* dQdp, double* dQdx) const {
  const double p = pressure(e);
  if (!has_ball()) {
    *dQdp = dcheck_dp(p);
    *dQdx = 0.0;
    return check_flow(p);
  }
  const double lift = e.s[3];
  if (!(lift > 0.0)) {
    *dQdp = *dQdx = 0.0;
    return 0.0;
  }
  // Q = c x φ(Δ) (x the lift up to full open), φ = Δ/(Δ² + Δ_t²)^¼,
  // φ′ = (½Δ² + Δ_t²)/(Δ² + Δ_t²)^(5/4), Δ = p_s − p
  const double x = std::min(lift, x_open_);
  const double d = p_s_ - p, r = d * d + dp_t_ * dp_t_;
  const double phi = d / std::pow(r, 0.25);
  *dQdp = -ball_c_ * x * (0.5 * d * d + dp_t_ * dp_t_) / std::pow(r, 1.25);
  *dQdx = lift < x_open_ ? ball_c_ * phi : 0.0;
  return ball_c_ * x * phi;
}

double HydraulicLashAdjuster::strain_energy_density(double p) const {
  // ∫ p′/β_eff dp′ with 1/β_eff = (a u² + b)/(u (c u + b)), u = p_ref + p′, a = (1 − α)/β,
  // b = α p_ref, c = 1 − α: (u − p_ref)(a u² + b)/(u(c u + b)) = (a/c) u + k₁ + A₁/u + A₂/(c u + b)
  // with k₁ = −a(p_ref + b/c)/c, A₁ = −p_ref, A₂ = b(1 − k₁) + c p_ref.
  auto eps = [&](double pg) {
    if (alpha_ == 0.0) return pg * pg / (2.0 * beta_);
    const double P0 = p_ref_, a = (1.0 - alpha_) / beta_, b = alpha_ * P0, c = 1.0 - alpha_;
    const double k1 = -a * (P0 + b / c) / c, A1 = -P0, A2 = b * (1.0 - k1) + c * P0;
    return a / (2.0 * c) * pg * (2.0 * P0 + pg) + k1 * pg + A1 * std::log1p(pg / P0) +
           A2 / c * std::log1p(c * pg / (c * P0 + b));
  };
  const double p_min = p_abs_min_ - p_ref_;
  if (alpha_ == 0.0 || p >= p_min) return eps(p);
  return eps(p_min) + (p * p - p_min * p_min) / (2.0 * bulk_modulus(p_min));
}

void HydraulicLashAdjuster::force(const ElementState& e, double* f) const {
  const double F = pressure(e) * A_ + P_ + k_ * travel(e);
  f[0] = -F;
  f[1] = F;
}

void HydraulicLashAdjuster::force_jacobian(const ElementState&, double* dfdx, double* dfdxd) const {
  // f = [−F, F], ∂δ/∂x = [1, −1]
  dfdx[0] = -k_, dfdx[1] = k_, dfdx[2] = k_, dfdx[3] = -k_;
  if (dfdxd) std::fill(dfdxd, dfdxd + 4, 0.0);
}

void HydraulicLashAdjuster::state_rate(const ElementState& e, double* sdot) const {
  const double p = pressure(e), V = chamber_volume(travel(e));
  double dQdp, dQdx;
  const double Q = inflow(e, &dQdp, &dQdx);
  const double R = A_ * (e.xd[0] - e.xd[1]) - leak_flow(p) + Q;
  sdot[0] = bulk_modulus(p) / V * R / p_ref_;
  sdot[1] = Q / V0_;
  sdot[2] = leak_flow(p) / V0_;
  if (has_ball()) {
    sdot[3] = e.s[4];
    sdot[4] = ball_acceleration(p, e.s[3], e.s[4]);
  }
}

void HydraulicLashAdjuster::state_jacobian(const ElementState& e, double* dgdx, double* dgdxd, double* dgds,
                                           double* dfds) const {
  const double p = pressure(e), delta = travel(e), V = chamber_volume(delta);
  double dQdp, dQdx;
  const double Q = inflow(e, &dQdp, &dQdx);
  const double R = A_ * (e.xd[0] - e.xd[1]) - leak_flow(p) + Q;
  const double beta = bulk_modulus(p);
  const int ms = states();
  const double dVdd = V0_ - A_ * delta > kMinVolume * V0_ ? -A_ : 0.0;
  // g = β R/(V p_ref): ∂g/∂δ = −β R dV/dδ /(V² p_ref), ∂g/∂δ̇ = β A/(V p_ref),
  // ∂g/∂s = p_ref ∂g/∂p = (dβ/dp R + β ∂R/∂p)/V
  const double gd = -beta * R * dVdd / (V * V * p_ref_), gv = beta * A_ / (V * p_ref_);
  // ms × 2 and ms × ms column-major, entry (l, c) at l + c·ms (rows: p, the pumped and the
  // leaked volume, the ball's lift and speed)
  std::fill(dgdx, dgdx + 2 * ms, 0.0);
  std::fill(dgdxd, dgdxd + 2 * ms, 0.0);
  std::fill(dgds, dgds + ms * ms, 0.0);
  std::fill(dfds, dfds + 2 * ms, 0.0);
  dgdx[0] = gd, dgdx[ms] = -gd;
  dgdxd[0] = gv, dgdxd[ms] = -gv;
  dgds[0] = (dbulk_dp(p) * R + beta * (-leak_ + dQdp)) / V;
  dgds[1] = dQdp * p_ref_ / V0_;
  dgds[2] = leak_ * p_ref_ / V0_;
  dfds[0] = -A_ * p_ref_, dfds[1] = A_ * p_ref_;  // 2 × ms: F = p A + …, p = p_ref(s₀ − 1)
  if (has_ball()) {
    const double x = e.s[3];
    dgds[0 + 3 * ms] = beta * dQdx / (V * p_ref_);
    dgds[1 + 3 * ms] = dQdx / V0_;
    dgds[3 + 4 * ms] = 1.0;
    dgds[4 + 0 * ms] = -As_ * p_ref_ / mb_;
    dgds[4 + 3 * ms] = -(kb_ + (x < 0.0 ? ks_ : 0.0)) / mb_;
    dgds[4 + 4 * ms] = -cb_ / mb_;
  }
}

void HydraulicLashAdjuster::initial_states(double* s0) const {
  s0[0] = 1.0 + p0_ / p_ref_;
  s0[1] = s0[2] = 0.0;
  if (has_ball()) {  // at rest: (p_s − p₀)A_s − P_b = k_b x (+ k_s x on the seat)
    const double F0 = (p_s_ - p0_) * As_ - Pb_;
    s0[3] = F0 > 0.0 ? F0 / kb_ : F0 / (kb_ + ks_);
    s0[4] = 0.0;
  }
}

double HydraulicLashAdjuster::stored_energy(const ElementState& e) const {
  const double d = travel(e);
  double V = 0.5 * k_ * d * d + P_ * d + chamber_volume(d) * strain_energy_density(pressure(e));
  if (has_ball()) {
    const double x = e.s[3], w = e.s[4];
    V += 0.5 * mb_ * w * w + 0.5 * kb_ * x * x + Pb_ * x + (x < 0.0 ? 0.5 * ks_ * x * x : 0.0);
  }
  return V;
}

double HydraulicLashAdjuster::dissipated_power(const ElementState& e) const {
  const double p = pressure(e), delta = travel(e);
  const double dVdd = V0_ - A_ * delta > kMinVolume * V0_ ? -A_ : 0.0;
  double dQdp, dQdx;
  const double Q = inflow(e, &dQdp, &dQdx);
  double P = p * (leak_flow(p) - Q) - strain_energy_density(p) * dVdd * (e.xd[0] - e.xd[1]);
  if (has_ball()) P += cb_ * e.s[4] * e.s[4] - (p_s_ - p) * As_ * e.s[4];
  return P;
}

std::vector<std::string> HydraulicLashAdjuster::force_names() const {
  std::vector<std::string> n{name(), name() + "_pressure", name() + "_travel", name() + "_pumped", name() + "_leaked"};
  if (has_ball()) {
    n.push_back(name() + "_ball_lift");
    n.push_back(name() + "_check_flow");
  }
  return n;
}

void HydraulicLashAdjuster::forces(const ElementState& e, double* out) const {
  out[0] = pressure(e) * A_ + P_ + k_ * travel(e);
  out[1] = pressure(e);
  out[2] = travel(e);
  out[3] = V0_ * e.s[1];
  out[4] = V0_ * e.s[2];
  if (has_ball()) {
    out[5] = e.s[3];
    out[6] = ball_flow(pressure(e), e.s[3]);
  }
}

}  // namespace camdyn
