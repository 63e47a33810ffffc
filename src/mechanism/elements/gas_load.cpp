// camdyn — the gas load on a valve head (gas_load.hpp has the law).
#include "mechanism/elements/gas_load.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "camdyn/network.hpp"
#include "scene/key_table.hpp"  // format_number

namespace camdyn {

namespace {
constexpr double kDegPerRad = 57.295779513082320876798154814105;
}

GasLoad::GasLoad(const ElementSpec& spec, std::string name, const CamSpec& cam)
    : Element(std::move(name), 2), phi_(spec.crank_angles_deg), p_(spec.pressures), area_(spec.area),
      ratio_(spec.crank_ratio), offset_(spec.crank_offset_deg), drive_(cam), nodes_(spec.nodes) {}

std::string GasLoad::describe() const {
  std::ostringstream d;
  d << "gas_load '" << name() << "' [" << nodes_.at(0) << " on " << nodes_.at(1) << "] area "
    << detail::format_number(area_) << ", pressure table of " << phi_.size() << " points over "
    << detail::format_number(360.0 * ratio_) << " crank deg, crank = " << detail::format_number(ratio_)
    << " × cam angle + " << detail::format_number(offset_) << " deg";
  return d.str();
}

double GasLoad::crank_angle_deg(double t) const {
  const double cycle = 360.0 * ratio_;
  double phi = std::fmod(ratio_ * drive_.theta(t) * kDegPerRad + offset_, cycle);
  if (phi < 0) phi += cycle;
  return phi;
}

double GasLoad::pressure(double phi) const {
  const std::size_t n = phi_.size();
  if (n == 1) return p_[0];
  const double cycle = 360.0 * ratio_;
  if (phi < phi_.front() || phi >= phi_.back()) {  // the wrap segment: last → first + cycle
    const double x0 = phi_.back(), x1 = phi_.front() + cycle;
    const double x = phi < phi_.front() ? phi + cycle : phi;
    return p_.back() + (p_.front() - p_.back()) * (x - x0) / (x1 - x0);
  }
  const std::size_t k = std::size_t(std::upper_bound(phi_.begin(), phi_.end(), phi) - phi_.begin()) - 1;
  return p_[k] + (p_[k + 1] - p_[k]) * (phi - phi_[k]) / (phi_[k + 1] - phi_[k]);
}

void GasLoad::force(const ElementState& e, double* f) const {
  const double F = pressure(crank_angle_deg(e.t)) * area_;
  f[0] = -F;
  f[1] = F;
}

void GasLoad::force_jacobian(const ElementState&, double* dfdx, double* dfdxd) const {
  for (int i = 0; i < 4; ++i) {
    dfdx[i] = 0.0;
    if (dfdxd) dfdxd[i] = 0.0;
  }
}

double GasLoad::dissipated_power(const ElementState& e) const {
  return pressure(crank_angle_deg(e.t)) * area_ * (e.xd[0] - e.xd[1]);
}

void GasLoad::forces(const ElementState& e, double* out) const { out[0] = pressure(crank_angle_deg(e.t)) * area_; }

}  // namespace camdyn
