// camdyn — order analysis (spectrum.hpp).
#include "camdyn/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "cam/format.hpp"
#include "camdyn/scene.hpp"

namespace camdyn {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
}

void SpectrumOptions::validate() const {
  if (revolutions < 0)
    throw SceneError("SpectrumOptions", 0, "revolutions", std::to_string(revolutions), "must be >= 0 (0: all)");
  if (samples_per_revolution < 8 || samples_per_revolution > (1 << 20))
    throw SceneError("SpectrumOptions", 0, "samples_per_revolution", std::to_string(samples_per_revolution),
                     "must be between 8 and 1048576");
  if (!(max_order > 0) || !(max_order <= 0.5 * samples_per_revolution))
    throw SceneError("SpectrumOptions", 0, "max_order", fmt_num(max_order),
                     "must be > 0 and <= samples_per_revolution / 2 = " +
                         std::to_string(samples_per_revolution / 2));
}

OrderSpectrum order_spectrum(const std::vector<double>& theta, const std::vector<double>& y,
                             const SpectrumOptions& o) {
  o.validate();
  if (theta.size() != y.size())
    throw SceneError("order_spectrum", 0, "y", std::to_string(y.size()) + " samples",
                     "must have as many samples as theta (" + std::to_string(theta.size()) + ")");
  if (theta.size() < 2) throw SceneError("order_spectrum", 0, "theta", "too few samples", "needs >= 2 samples");
  const double dir = theta.back() >= theta.front() ? 1.0 : -1.0;
  std::vector<double> phi(theta.size());
  for (std::size_t i = 0; i < theta.size(); ++i) {
    phi[i] = dir * (theta[i] - theta.front());
    if (i > 0 && phi[i] < phi[i - 1])
      throw SceneError("order_spectrum", 0, "theta", fmt_num(theta[i]),
                       "the cam angle must be monotone (the cam turns one way at sample " + std::to_string(i) + ")");
  }
  const int complete = int(std::floor(phi.back() / kTwoPi + 1e-9));
  if (complete < 1)
    throw SceneError("order_spectrum", 0, "theta", fmt_num(phi.back()) + " rad",
                     "the record covers less than one revolution");
  const int R = o.revolutions > 0 ? std::min(o.revolutions, complete) : complete;
  const double phi0 = phi.back() - kTwoPi * R;  // the last R revolutions
  const int S = o.samples_per_revolution, N = R * S;
  std::vector<double> u(static_cast<std::size_t>(N));
  std::size_t k = 0;
  for (int i = 0; i < N; ++i) {
    const double p = phi0 + kTwoPi * R * double(i) / double(N);
    while (k + 2 < phi.size() && phi[k + 1] < p) ++k;
    const double a = phi[k], b = phi[k + 1];
    const double w = b > a ? std::clamp((p - a) / (b - a), 0.0, 1.0) : 0.0;
    u[static_cast<std::size_t>(i)] = y[k] + w * (y[k + 1] - y[k]);
  }
  OrderSpectrum s;
  s.revolutions = R;
  s.phi_start = phi0;
  const int J = int(std::floor(o.max_order * R + 1e-9));
  for (int j = 0; j <= J; ++j) {
    // X_j = Σ u_i e^{−2πi j i/N}, the twiddle by recurrence in long double
    std::complex<long double> X = 0, w = 1;
    const std::complex<long double> step = std::polar<long double>(1.0L, -kTwoPi * (long double)j / (long double)N);
    for (int i = 0; i < N; ++i) {
      X += (long double)u[static_cast<std::size_t>(i)] * w;
      if ((i & 255) == 255) w = std::polar<long double>(1.0L, -kTwoPi * (long double)j * (long double)(i + 1) / (long double)N);
      else w *= step;
    }
    const double mag = double(std::abs(X)) / N;
    s.order.push_back(double(j) / R);
    s.amplitude.push_back(j == 0 ? mag : 2 * mag);
    s.phase_deg.push_back(j == 0 ? 0.0 : double(std::arg(X)) * 360.0 / kTwoPi);
  }
  return s;
}

}  // namespace camdyn
