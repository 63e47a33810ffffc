// camdyn — Hertz line contact (see include/camdyn/hertz.hpp).
#include "camdyn/hertz.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace camdyn {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

double contact_modulus(double E1, double nu1, double E2, double nu2) {
  if (!(E1 > 0 && E2 > 0 && std::isfinite(E1) && std::isfinite(E2)))
    throw std::invalid_argument("contact_modulus: Young's moduli must be finite and > 0");
  if (!(nu1 >= 0 && nu1 < 0.5 && nu2 >= 0 && nu2 < 0.5))
    throw std::invalid_argument("contact_modulus: Poisson ratios must be in [0, 0.5)");
  return 1.0 / ((1 - nu1 * nu1) / E1 + (1 - nu2 * nu2) / E2);
}

HertzLine hertz_line(double F, double width, double R1, double R2, double E_star) {
  if (!(width > 0)) throw std::invalid_argument("hertz_line: width must be > 0");
  if (!(E_star > 0)) throw std::invalid_argument("hertz_line: E* must be > 0");
  const double k = (std::isinf(R1) ? 0.0 : 1.0 / R1) + (std::isinf(R2) ? 0.0 : 1.0 / R2);
  if (!(k > 0))
    throw std::invalid_argument("hertz_line: 1/R1 + 1/R2 = " + std::to_string(k) +
                                " must be > 0 (two planes, or a concave surface that conforms)");
  HertzLine h;
  if (!(F > 0)) return h;
  const double P = F / width, Rp = 1.0 / k;
  h.half_width = std::sqrt(4.0 * P * Rp / (kPi * E_star));
  h.max_pressure = std::sqrt(P * E_star / (kPi * Rp));
  return h;
}

}  // namespace camdyn
