// The summary's tolerance words on cvode-bdf say the BDF orders the run was given: a table of
// follower kind × contact method × rtol → the exact words (written here), and the words'
// largest order against the largest order CVODE reported using for a step
// (CVodeGetLastOrder after every step, RunRecord::max_bdf_order_used): an engine's own
// count, not the rule that set the limit. Each run is short (a few ms of cam motion) but long
// enough for CVODE to raise its order to the limit on the smooth stretch after the start.
// The criteria's words for a seat criterion with nothing to judge follow the follower's
// stop contacts.
#include <gtest/gtest.h>

#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "camdyn/follower_system.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "contact/contact_run.hpp"
#include "mechanism/mechanism.hpp"
#include "run/summary_builder.hpp"

using namespace camdyn;

namespace {

std::string example(const std::string& file) { return std::string(CAMDYN_SOURCE_DIR) + "/examples/" + file; }

const std::string kLee =
    "; contact.tol_u 1e-10 bounds the displacement residual of a held step, and the contact force's "
    "acceleration-level error is held to rtol·|F| + 2 tol_u/(M* h²)";
const std::string kDamps =
    " (A-stable; they damp the follower's resolved modes, so the global error grows faster than on the "
    "one-step engines)";
const std::string kStabLim =
    " (CVODE's stability-limit detection lowers the order where orders 3-5 go unstable on the follower's "
    "stiff modes)";

struct Row {
  const char* file;   // example scene
  const char* model;  // contact.model
  const char* rtol;
  const char* t_end;
  std::string words;  // Summary::tolerance_meaning
  bool warned;        // Summary::tolerance_warning given
};

int words_max_order(const std::string& words) {
  std::smatch m;
  if (!std::regex_search(words, m, std::regex("BDF orders 1-([0-9])"))) return -1;
  return std::stoi(m[1]);
}

}  // namespace

TEST(ToleranceWords, CvodeBdfWordsStateTheOrderTheRunWasGiven) {
  const std::string r6 = "rtol 1e-06, atol 1e-12 bound each step's local error of BDF orders 1-";
  const std::string r9 = "rtol 1e-09, atol 1e-12 bound each step's local error of BDF orders 1-";
  const std::vector<Row> table = {
      // a rigid follower: Lee in CVODE ≤ 4, the event and penalty methods ≤ 5
      {"case_A.toml", "lee", "1e-6", "0.005", r6 + "4" + kLee, false},
      {"case_A.toml", "event", "1e-6", "0.005", r6 + "5", false},
      {"case_A.toml", "penalty", "1e-6", "0.005", r6 + "5", false},
      {"case_A.toml", "holonomic", "1e-6", "0.005", r6 + "4", false},  // runs Lee in CVODE
      // an elastic bar: ≤ 2 at rtol > 1e-8 for every method; ≤ 5 with stability-limit
      // detection at rtol ≤ 1e-8
      {"case_B1.toml", "lee", "1e-6", "0.001", r6 + "2" + kDamps + kLee, true},
      {"case_B1.toml", "event", "1e-6", "0.001", r6 + "2" + kDamps, true},
      {"case_B1.toml", "event", "1e-9", "0.003", r9 + "5" + kStabLim, false},
      // a valve train (network of several unknowns, no stiff-mode order cap)
      {"ohc_bucket_tappet.toml", "lee", "1e-6", "0.012", r6 + "4" + kLee, false},
      {"ohc_bucket_tappet.toml", "event", "1e-6", "0.012", r6 + "5", false},
      {"ohc_bucket_tappet.toml", "penalty", "1e-6", "0.012", r6 + "5", false},
  };
  for (const Row& row : table) {
    SCOPED_TRACE(std::string(row.file) + " " + row.model + " rtol " + row.rtol);
    const Scene sc = load_scene_file(
        example(row.file), {"solver.integrator=cvode-bdf", std::string("contact.model=") + row.model,
                            std::string("solver.rtol=") + row.rtol, "solver.atol=1e-12", "contact.tol_u=1e-10",
                            std::string("run.t_end=") + row.t_end});
    auto mech = std::make_shared<const Mechanism>(sc);
    auto method = detail::make_contact_method(sc, mech, nullptr, nullptr);
    const detail::RunRecord& rec = method->run();
    ASSERT_TRUE(rec.finished) << rec.message;
    const Summary s = detail::build_summary(sc, *mech, {}, rec, method->parts());
    EXPECT_EQ(s.tolerance_meaning, row.words);
    EXPECT_EQ(!s.tolerance_warning.empty(), row.warned) << s.tolerance_warning;
    EXPECT_EQ(words_max_order(s.tolerance_meaning), rec.max_bdf_order_used) << rec.steps << " steps";
  }
}

namespace {

// One mass on a spring on the cam; with `stop`, a stop contact 1 m above it (never reached).
struct MassOnSpring : FollowerSystem {
  bool stop = false;
  int size() const override { return 1; }
  std::vector<FollowerContact> contacts() const override {
    FollowerContact c;
    c.name = "cam";
    c.row = {1.0};
    if (!stop) return {c};
    FollowerContact s;
    s.name = "stop";
    s.row = {-1.0};
    s.clearance = 1.0;
    s.cam = false;
    return {c, s};
  }
  void force(double, const double* q, const double*, double* r) const override { r[0] = -(150.0 + 2e4 * q[0]); }
  void solve_mass(const double* b, double* x) const override { x[0] = b[0] / 0.1; }
};

std::string seat_note(const Summary& s) {
  for (const CriterionResult& c : s.criteria)
    if (c.name == "seating_velocity") return c.note;
  return "(no seating_velocity criterion)";
}

Scene circle_cam_with_seat_criterion() {
  Scene s = default_scene();
  s.cam.profile = CamProfileKind::Circle;
  s.cam.radius = 0.02;
  s.cam.eccentricity = 0.004;
  s.cam.theta0_deg = 180.0;
  s.cam.speed_rev_s = 20.0;
  s.run.t_end = 2e-3;
  s.criteria.max_seating_velocity = 1.0;
  return s;
}

}  // namespace

// A seat criterion with nothing to judge says why: a follower without stop contacts, one
// whose stop contacts are no seat of the scene's [[contacts]] (a user follower's), a scene
// with a seat that saw no impact.
TEST(ToleranceWords, SeatCriterionNoteFollowsTheFollowersStopContacts) {
  const Scene sc = circle_cam_with_seat_criterion();
  auto plain = std::make_shared<MassOnSpring>();
  auto stopped = std::make_shared<MassOnSpring>();
  stopped->stop = true;
  const Summary a = Simulator(sc, plain).run();
  const Summary b = Simulator(sc, stopped).run();
  ASSERT_TRUE(a.finished) << a.message;
  ASSERT_TRUE(b.finished) << b.message;
  EXPECT_EQ(seat_note(a), "no seat: the follower has no stop contact");
  EXPECT_EQ(seat_note(b),
            "no seat: seat landings are measured on the scene's [[contacts]] stops below a node, and the "
            "follower's stop contact is not one");
  // the bucket tappet's seat, 2 ms into the base circle: closed, no impact
  const Scene ohc = load_scene_file(example("ohc_bucket_tappet.toml"),
                                    {"run.t_end=0.002", "criteria.max_seating_velocity=1"});
  const Summary c = simulate(ohc).summary;
  ASSERT_TRUE(c.finished) << c.message;
  EXPECT_TRUE(c.landings.empty());
  EXPECT_EQ(seat_note(c), "no seat impact in the run");
}
