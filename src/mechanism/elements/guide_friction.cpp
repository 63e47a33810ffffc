// camdyn — Coulomb friction in a guide, regularised (guide_friction.hpp has the law).
#include "mechanism/elements/guide_friction.hpp"

#include <cmath>
#include <sstream>

#include "camdyn/network.hpp"
#include "scene/key_table.hpp"  // format_number

namespace camdyn {

GuideFriction::GuideFriction(const ElementSpec& spec, std::string name)
    : Element(std::move(name), 2), muN_(spec.friction_coefficient * spec.normal_load), vs_(spec.velocity_scale),
      nodes_(spec.nodes) {}

std::string GuideFriction::describe() const {
  std::ostringstream d;
  d << "guide_friction '" << name() << "' [" << nodes_.at(0) << " in " << nodes_.at(1) << "] μN "
    << detail::format_number(muN_) << ", regularised below v_s " << detail::format_number(vs_);
  return d.str();
}

void GuideFriction::force(const ElementState& e, double* f) const {
  const double F = -muN_ * std::tanh((e.xd[0] - e.xd[1]) / vs_);
  f[0] = F;
  f[1] = -F;
}

void GuideFriction::force_jacobian(const ElementState& e, double* dfdx, double* dfdxd) const {
  for (int i = 0; i < 4; ++i) dfdx[i] = 0.0;
  if (!dfdxd) return;
  const double th = std::tanh((e.xd[0] - e.xd[1]) / vs_);
  const double c = muN_ / vs_ * (1.0 - th * th);  // the local damper rate
  dfdxd[0] = -c, dfdxd[1] = c, dfdxd[2] = c, dfdxd[3] = -c;
}

double GuideFriction::dissipated_power(const ElementState& e) const {
  const double v = e.xd[0] - e.xd[1];
  return muN_ * std::tanh(v / vs_) * v;
}

void GuideFriction::forces(const ElementState& e, double* out) const {
  out[0] = -muN_ * std::tanh((e.xd[0] - e.xd[1]) / vs_);
}

}  // namespace camdyn
