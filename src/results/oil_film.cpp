// camdyn — elastohydrodynamic film at a line contact (oil_film.hpp).
#include "results/oil_film.hpp"

#include <cmath>
#include <string>

#include "cam/format.hpp"
#include "camdyn/scene.hpp"

namespace camdyn {

void Lubricant::validate() const {
  if (!(viscosity > 0) || !std::isfinite(viscosity))
    throw SceneError("Lubricant", 0, "viscosity", fmt_num(viscosity), "must be > 0");
  if (!(pressure_viscosity >= 0) || !std::isfinite(pressure_viscosity))
    throw SceneError("Lubricant", 0, "pressure_viscosity", fmt_num(pressure_viscosity), "must be >= 0");
  if (!(composite_roughness >= 0) || !std::isfinite(composite_roughness))
    throw SceneError("Lubricant", 0, "composite_roughness", fmt_num(composite_roughness), "must be >= 0");
}

double effective_modulus(double E_a, double nu_a, double E_b, double nu_b) {
  return 2.0 / ((1 - nu_a * nu_a) / E_a + (1 - nu_b * nu_b) / E_b);
}

double line_contact_min_film(double w, double Rx, double u, const Lubricant& oil, double Ep) {
  if (!(w > 0) || !(Rx > 0)) return NAN;
  u = std::abs(u);
  if (u == 0) return 0.0;
  const double W = w / (Ep * Rx), U = oil.viscosity * u / (Ep * Rx), G = oil.pressure_viscosity * Ep;
  return Rx * 1.714 * std::pow(W, -0.128) * std::pow(U, 0.694) * std::pow(G, 0.568);
}

double flat_face_entrainment(double omega, double rb, double s, double sdd) { return -0.5 * omega * (rb + s + 2 * sdd); }

double roller_entrainment(double omega, double rb, double rr, double s, double sd, double rho) {
  const double Vc = std::abs(omega) * std::hypot(rb + rr + s, sd);
  return Vc * rho / (rho + rr);
}

}  // namespace camdyn
