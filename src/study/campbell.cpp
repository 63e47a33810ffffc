// camdyn — Campbell diagrams (camdyn/campbell.hpp): order spectra of one column over a
// range of cam speeds, and the surge lines of the springs with coil masses.
#include "camdyn/campbell.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>

#include "camdyn/batch.hpp"
#include "camdyn/simulator.hpp"
#include "cam/format.hpp"  // fmt

namespace camdyn {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;

[[noreturn]] void bad(const std::string& field, const std::string& value, const std::string& rule) {
  throw SceneError("CampbellOptions", 0, field, value, rule);
}
}  // namespace

void CampbellOptions::validate() const {
  if (column.empty()) bad("column", "\"\"", "must name a history column");
  if (speeds_rev_s.size() < 2) bad("speeds_rev_s", std::to_string(speeds_rev_s.size()) + " speeds", "needs at least 2");
  for (std::size_t i = 0; i < speeds_rev_s.size(); ++i) {
    const double v = speeds_rev_s[i];
    if (!(std::isfinite(v) && v > 0)) bad("speeds_rev_s", detail::fmt(v), "every speed must be finite and > 0");
    if (i && !(v > speeds_rev_s[i - 1])) bad("speeds_rev_s", detail::fmt(v), "must increase");
  }
  if (settle_revolutions < 0) bad("settle_revolutions", std::to_string(settle_revolutions), "must be >= 0");
  if (revolutions < 1) bad("revolutions", std::to_string(revolutions), "must be >= 1");
  if (samples_per_revolution < 16)
    bad("samples_per_revolution", std::to_string(samples_per_revolution), "must be >= 16");
  if (!(max_order > 0 && max_order <= samples_per_revolution / 2))
    bad("max_order", detail::fmt(max_order),
        "must be > 0 and <= samples_per_revolution / 2 = " + std::to_string(samples_per_revolution / 2));
}

std::vector<CampbellLine> surge_lines(const Scene& scene, int modes) {
  std::vector<CampbellLine> lines;
  const auto& els = scene.network.elements;
  for (std::size_t i = 0; i < els.size(); ++i) {
    const ElementSpec& e = els[i];
    if (e.kind != ElementKind::Spring || e.masses < 1 || !(e.mass > 0) || !(e.stiffness > 0)) continue;
    // the lumped chain between held ends: N inner masses m_s/(N+1), N+1 springs (N+1)k
    const int N = e.masses;
    const double kk = (N + 1) * e.stiffness, mm = e.mass / (N + 1);
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);
    for (int r = 0; r < N; ++r) {
      K(r, r) = 2 * kk / mm;
      if (r) K(r, r - 1) = K(r - 1, r) = -kk / mm;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, Eigen::EigenvaluesOnly);
    const std::string name = e.name.empty() ? "spring #" + std::to_string(i + 1) : e.name;
    for (int k = 0; k < std::min(modes, N); ++k)
      lines.push_back({name + " surge " + std::to_string(k + 1), std::sqrt(eig.eigenvalues()[k]) / kTwoPi});
  }
  return lines;
}

CampbellDiagram campbell(const Scene& scene, const CampbellOptions& o, const std::atomic<bool>* stop) {
  o.validate();
  SpectrumOptions so;
  so.revolutions = o.revolutions;
  so.samples_per_revolution = o.samples_per_revolution;
  so.max_order = o.max_order;
  so.validate();
  std::vector<Scene> scenes;
  for (double v : o.speeds_rev_s) {
    Scene s = scene;
    s.cam.speed_rev_s = v;
    s.rpm_per_rev_s = scene.rpm_per_rev_s;
    s.run.t_end = double(o.settle_revolutions + o.revolutions) / v;
    s.run.output_dt = 1.0 / (v * o.samples_per_revolution);
    scenes.push_back(std::move(s));
  }
  // the column: a base one, or an extra one of this scene (the same for every speed)
  const std::vector<std::string>& base = history_columns();
  int ib = int(std::find(base.begin(), base.end(), o.column) - base.begin()), ie = -1;
  if (ib >= int(base.size())) {
    ib = -1;
    const std::vector<std::string> extra = Simulator(scenes.front()).extra_columns();
    ie = int(std::find(extra.begin(), extra.end(), o.column) - extra.begin());
    if (ie >= int(extra.size())) {
      std::string all;
      for (const auto& c : base) all += (all.empty() ? "" : ", ") + c;
      for (const auto& c : extra) all += ", " + c;
      bad("column", o.column, "is not a history column of this scene (columns: " + all + ")");
    }
  }
  auto value = [&](const HistoryRow& r) {
    if (ie >= 0) return r.extra[std::size_t(ie)];
    switch (ib) {
      case 0: return r.t;
      case 1: return r.theta;
      case 2: return r.u_c;
      case 3: return r.v_c;
      case 4: return r.a_c;
      case 5: return r.contact_force;
      case 6: return r.gap;
      case 7: return double(r.in_contact);
      case 8: return r.kinetic;
      case 9: return r.potential;
      case 10: return r.work_cam;
      default: return r.dissipated;
    }
  };
  const std::vector<RunResult> runs = simulate_batch(scenes, o.threads, {}, stop);
  CampbellDiagram d;
  d.column = o.column;
  d.speed_rev_s = o.speeds_rev_s;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const RunResult& r = runs[k];
    if (!r.summary.finished)
      bad("speeds_rev_s", detail::fmt(o.speeds_rev_s[k]),
          "the run at this speed did not finish: " + r.summary.message);
    std::vector<double> th, y;
    th.reserve(r.rows.size());
    y.reserve(r.rows.size());
    for (const HistoryRow& row : r.rows) {
      if (!th.empty() && row.theta == th.back()) continue;  // an event's two sides
      th.push_back(row.theta);
      y.push_back(value(row));
    }
    const OrderSpectrum s = order_spectrum(th, y, so);
    if (d.order.empty()) d.order = s.order;
    d.amplitude.push_back(s.amplitude);
    d.runs.push_back(r.summary);
  }
  d.lines = surge_lines(scene);
  return d;
}

}  // namespace camdyn
