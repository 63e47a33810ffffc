// camdyn — Campbell diagrams (docs/guide/sweeps.md "Campbell diagram"): the order spectrum
// of one history column at each cam speed of a range (camdyn/spectrum.hpp), with the
// surge frequencies of the scene's springs with coil masses as lines order = f / n.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/summary.hpp"
#include "camdyn/spectrum.hpp"

namespace camdyn {

/// Options of campbell(). Defaults in brackets.
struct CampbellOptions {
  /// The history column analysed ["contact_force"]: a base column or an extra one
  /// (F_<contact>, u_<node>, force_<element>, …; Simulator::extra_columns()).
  std::string column = "contact_force";
  /// Camshaft speeds [rev/s], > 0, at least 2, increasing.
  std::vector<double> speeds_rev_s;
  /// Revolutions run before the analysed ones (the start's transient) [2], ≥ 0.
  int settle_revolutions = 2;
  /// Revolutions analysed [2], ≥ 1.
  int revolutions = 2;
  /// Rows per revolution of each run (run.output_dt = 1/(n·this)) [512], ≥ 16.
  int samples_per_revolution = 512;
  /// Highest order reported [32], > 0, ≤ samples_per_revolution / 2.
  double max_order = 32;
  /// Worker threads (run_batch) [0: all cores].
  int threads = 0;
  /// @throws SceneError naming the field, its value and the rule.
  void validate() const;
};

/// A line of the diagram: a natural frequency [Hz] that does not depend on the cam speed,
/// drawn at order = frequency / speed.
struct CampbellLine {
  std::string name;  ///< "valve_spring surge 1"
  double frequency_hz = 0;
};

/// The diagram: one spectrum per speed (amplitude[k][j] at order[j], the same orders for
/// every speed), the runs' summaries and the lines.
struct CampbellDiagram {
  std::string column;
  std::vector<double> speed_rev_s;
  std::vector<double> order;
  std::vector<std::vector<double>> amplitude;
  std::vector<Summary> runs;
  std::vector<CampbellLine> lines;
};

/// The surge frequencies of every spring with coil masses in `scene`'s network: the
/// eigenfrequencies of its lumped coil chain with both ends held (the valve on its seat),
/// `modes` per spring. For N coil masses the first tends to ½√(k/m_s) as N grows.
/// @pre validate(scene) passed.
std::vector<CampbellLine> surge_lines(const Scene& scene, int modes = 3);

/// Runs `scene` at every speed of `options` (cam.speed_rev_s set, run.t_end the settle plus
/// analysed revolutions, rows at samples_per_revolution per revolution), in parallel, and
/// returns the order spectra of `options.column` over the analysed revolutions.
/// @throws SceneError for bad options, an invalid scene or an unknown column; a run that
///       does not finish throws SceneError naming its speed and message.
CampbellDiagram campbell(const Scene& scene, const CampbellOptions& options,
                         const std::atomic<bool>* stop = nullptr);

}  // namespace camdyn
