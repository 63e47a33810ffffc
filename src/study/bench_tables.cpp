// camdyn — the work–precision benchmark's tables (bench.hpp): its named scenes, the rows
// as CSV, and the headlines (the cheapest Lee run against the cheapest other method at
// equal accuracy).
#include <cmath>
#include <string>
#include <vector>

#include "camdyn/simulator.hpp"
#include "study/bench.hpp"
#include "study/bench_compare.hpp"

namespace camdyn {

namespace bench_detail {

namespace {

/// Cheapest finished run of `method` in `scene` (on `engine`, if not empty) with
/// err_force ≤ target; null if none.
const BenchRow* cheapest(const std::vector<BenchRow>& rows, const std::string& scene,
                         const std::string& method, double target, const std::string& engine = "") {
  const BenchRow* best = nullptr;
  for (const auto& r : rows) {
    if (r.scene != scene || r.method != method || !r.finished) continue;
    if (!engine.empty() && r.engine != engine) continue;
    if (!(r.err_force <= target)) continue;
    if (!best || r.cpu_seconds < best->cpu_seconds) best = &r;
  }
  return best;
}

std::string describe(const BenchRow& r) {
  std::string s = r.method + " " + r.engine;
  if (r.method == "lee") s += " tol_u " + g3(r.tol);
  if (!std::isnan(r.max_step)) s += " max_step " + g3(r.max_step);
  if (r.method == "penalty")
    s += " " + r.variant + " k_p " + g3(r.kp) + " c_p " + g3(r.cp) + " rtol " + g3(r.tol);
  if (r.method == "event" || r.method == "holonomic") s += " rtol " + g3(r.tol);
  return s + " (" + g3(r.cpu_seconds) + " s, err_F " + g3(r.err_force) + ", TV/TV_ref " +
         g3(r.osc_index) + ")";
}

/// The goal of a headline (issue 36): Lee against the best penalty at equal accuracy, ≥ 50×
/// on case A and ≥ 10× on the stiff bar; no goal elsewhere (NaN).
double headline_goal(const std::string& scene, const std::string& versus) {
  if (versus != "penalty") return kNaN;
  if (scene == "A") return 50.0;
  if (scene == "stiff") return 10.0;
  return kNaN;
}

}  // namespace

BenchHeadline headline(const std::vector<BenchRow>& rows, const std::string& scene,
                       const std::string& versus) {
  BenchHeadline h;
  h.scene = scene;
  h.versus = versus;
  h.target = kHeadlineTarget;
  h.goal = headline_goal(scene, versus);
  const BenchRow* lee = cheapest(rows, scene, "lee", h.target);
  const BenchRow* other = cheapest(rows, scene, versus, h.target);
  if (lee) h.lee = describe(*lee);
  if (other) h.other = describe(*other);
  const std::string at = "at contact-force error ≤ " + g3(h.target);
  if (!lee) {
    h.verdict = "no Lee run reaches it";
    h.text = versus + "/Lee CPU " + at + ": no Lee run reaches it";
    return h;
  }
  if (!other) {
    h.verdict = "no " + versus + " run reaches it";
    h.text = versus + "/Lee CPU " + at + ": no " + versus + " run reaches it (cheapest Lee: " +
             h.lee + ")";
    return h;
  }
  h.ratio = other->cpu_seconds / lee->cpu_seconds;
  if (std::isnan(h.goal))
    h.verdict = "no goal";
  else
    h.verdict = h.ratio >= h.goal ? "goal met" : "goal not met";
  h.text = versus + "/Lee CPU " + at + " = " + g3(h.ratio) +
           (std::isnan(h.goal) ? std::string() : " (goal ≥ " + g3(h.goal) + ": " + h.verdict + ")") +
           "; cheapest Lee: " + h.lee + "; cheapest " + versus + ": " + h.other;
  return h;
}


/// The rule of the reference: its checked error (the reference-check row's distance to
/// it) at least 10× below a row's error. Each finished row of `label` whose err_force,
/// err_force_pointwise or impulse_err is not gets a note naming the column and the
/// factor (that error is not resolved by the reference). A check at round-off (≤ 1e-12)
/// resolves every error.
void flag_unresolved(std::vector<BenchRow>& rows, const std::string& label) {
  const BenchRow* chk = nullptr;
  for (const auto& r : rows)
    if (r.scene == label && r.method == "reference-check" && r.finished) chk = &r;
  if (!chk) return;
  const BenchRow c = *chk;
  for (auto& r : rows) {
    if (r.scene != label || r.method == "reference-check" || !r.finished) continue;
    std::string cols;
    auto test = [&](const char* name, double e, double ce) {
      if (std::isfinite(e) && std::isfinite(ce) && ce > 1e-12 && e < 10 * ce)
        cols += std::string(cols.empty() ? "" : ", ") + name + " " + g3(e / ce) + "×";
    };
    test("err_F", r.err_force, c.err_force);
    test("err_F_pw", r.err_force_pointwise, c.err_force_pointwise);
    test("impulse_err", r.impulse_err, c.impulse_err);
    if (!cols.empty())
      r.note += (r.note.empty() ? "" : "; ") +
                std::string("within 10× of the reference's checked error: ") + cols;
  }
}


}  // namespace bench_detail

using namespace bench_detail;

bool is_bench_case(const std::string& name) {
  return name == "A" || name == "A7" || name == "B1" || name == "B2" || name == "stiff" ||
         name == "B1_1000";
}

Scene bench_case(const std::string& name) {
  if (name == "A7") {
    Scene s = paper_case("A");
    s.title = "Case A7 \u2014 rigid follower, 7 rev/s: separates and lands once per revolution";
    s.cam.speed_rev_s = 7.0;
    return s;
  }
  if (name == "stiff") {  // examples/stiff_bar.toml (a test checks they are equal)
    Scene s = paper_case("B2");
    s.title = "Stiff bar: E = 5e8, 200 elements, 5 rev/s";
    s.follower.youngs_modulus = 5e8;
    s.follower.elements = 200;
    s.contact.tol_u = 1e-7;
    s.solver.integrator = Integrator::ArkodeDirk;
    s.solver.rtol = 1e-6;
    s.run.t_end = 0.05;
    s.run.output_dt = 1e-4;
    return s;
  }
  if (name == "B1_1000") {
    Scene s = paper_case("B1");
    s.title = "Case B1 on 1000 elements";
    s.follower.elements = 1000;
    s.run.t_end = 0.05;
    return s;
  }
  if (!is_bench_case(name))
    throw SceneError("bench", 0, "scene", name, "a scene file or one of A, A7, B1, B2, stiff, B1_1000");
  return paper_case(name);
}

const std::vector<std::string>& bench_columns() {
  static const std::vector<std::string> c{
      "scene",     "method", "engine", "variant",  "tol",       "kp",          "cp",
      "cpu_seconds", "steps", "rhs_evals", "err_u", "err_force", "osc_index", "impulse_err",
      "event_err", "max_step", "finished",  "note", "err_force_pointwise", "impact_speed_err",
      "rejected_steps", "lin_setups", "nonlin_iters", "nonlin_conv_fails", "err_test_fails"};
  return c;
}

std::string bench_csv(const std::vector<BenchRow>& rows) {
  std::string s;
  for (const auto& c : bench_columns()) s += (s.empty() ? "" : ",") + c;
  s += "\n";
  for (const auto& r : rows) {
    s += csv_text(r.scene) + "," + r.method + "," + r.engine + "," + r.variant + "," +
         csv_num(r.tol) + "," + csv_num(r.kp) + "," + csv_num(r.cp) + "," +
         csv_num(r.cpu_seconds) + "," + std::to_string(r.steps) + "," +
         std::to_string(r.rhs_evals) + "," + csv_num(r.err_u) + "," + csv_num(r.err_force) +
         "," + csv_num(r.osc_index) + "," + csv_num(r.impulse_err) + "," +
         csv_num(r.event_err) + "," + csv_num(r.max_step) + "," + (r.finished ? "1" : "0") + "," + csv_text(r.note) + "," +
         csv_num(r.err_force_pointwise) + "," + csv_num(r.impact_speed_err) + "," + std::to_string(r.rejected_steps) + "," +
         std::to_string(r.lin_setups) + "," + std::to_string(r.nonlin_iters) + "," + std::to_string(r.nonlin_conv_fails) + "," + std::to_string(r.err_test_fails) + "\n";
  }
  return s;
}

std::string bench_headlines_csv(const std::vector<BenchHeadline>& headlines) {
  std::string s = "scene,versus,target,ratio,goal,verdict,lee,other\n";
  for (const auto& h : headlines)
    s += csv_text(h.scene) + "," + h.versus + "," + csv_num(h.target) + "," + csv_num(h.ratio) +
         "," + csv_num(h.goal) + "," + csv_text(h.verdict) + "," + csv_text(h.lee) + "," +
         csv_text(h.other) + "\n";
  return s;
}

}  // namespace camdyn
