// camdyn — order analysis of a history column (docs/guide/sweeps.md "Spectra"): the
// column resampled on a uniform grid of the cam's progress over whole revolutions, then
// its discrete Fourier transform in cam orders (cycles per camshaft revolution).
#pragma once

#include <string>
#include <vector>

namespace camdyn {

/// Options of order_spectrum(). Defaults in brackets.
struct SpectrumOptions {
  /// Revolutions analysed: the last this many complete revolutions of the record;
  /// 0 = every complete revolution [0].
  int revolutions = 0;
  /// Samples per revolution of the uniform resampling, ≥ 8 [1024]. Orders up to half
  /// of it are resolved.
  int samples_per_revolution = 1024;
  /// Highest order reported, > 0 [64]; at most samples_per_revolution / 2.
  double max_order = 64;
  /// @throws SceneError naming the field, its value and the rule.
  void validate() const;
};

/// The amplitude spectrum in cam orders: bins at order j/R (R revolutions analysed),
/// j = 0 … R·max_order; amplitude[0] is the mean, amplitude[j > 0] the single-sided
/// amplitude a of a·cos(order·φ + phase); phase_deg relative to the analysed window's start.
struct OrderSpectrum {
  std::vector<double> order, amplitude, phase_deg;
  int revolutions = 0;
  /// Cam progress [rad] where the analysed window starts.
  double phi_start = 0;
};

/// Order spectrum of samples y(θ): θ [rad] the cam angle column (monotone: the cam turns
/// one way), y the column. The record is linearly interpolated onto the uniform grid.
/// @throws SceneError when θ is not monotone, the sizes differ, or the record holds less
/// than one revolution.
OrderSpectrum order_spectrum(const std::vector<double>& theta, const std::vector<double>& y,
                             const SpectrumOptions& options = SpectrumOptions{});

}  // namespace camdyn
