// Tutorial 4 (C++): your own follower — a bucket tappet and a valve joined by an elastic stem,
// the valve closed by a progressive (cubic hardening) spring and stopped by its seat. Nothing
// in the library changes: the follower is a camdyn::FollowerSystem; the scene file gives the
// cam, the contact method, the engine and the run.
//
// usage: own_follower SCENE.toml OUT_DIR [SPEED_REV_S]
//   writes OUT_DIR/history.csv and OUT_DIR/events.csv; prints the summary.
#include <camdyn/follower_system.hpp>
#include <camdyn/output.hpp>
#include <camdyn/scene.hpp>
#include <camdyn/simulator.hpp>

#include <cstdio>
#include <memory>
#include <string>

// Unknowns q = (tappet, valve) lift [m], each from its rest position.
struct TappetValve : camdyn::FollowerSystem {
  double m_t = 0.045, m_v = 0.065;          // kg: tappet; valve with 1/3 of the spring coil
  double k_s = 5e7, c_s = 30.0;             // N/m, N·s/m: the stem, tappet on valve
  double P = 250.0, k = 35000.0, k3 = 2e8;  // N, N/m, N/m³: progressive valve spring

  int size() const override { return 2; }
  std::vector<camdyn::FollowerContact> contacts() const override {
    camdyn::FollowerContact cam, seat;
    cam.name = "cam";  // gap = q_tappet + lash − X_C(t): history F_cam, gap_cam, in_cam
    cam.row = {1.0, 0.0};
    cam.clearance = 0.2e-3;  // m of valve lash
    seat.name = "seat";  // gap = q_valve: the valve cannot go below its seat
    seat.row = {0.0, 1.0};
    seat.cam = false;
    return {cam, seat};
  }
  // r(t, q, q̇): every force but the contacts'. The stem pushes the valve by its compression;
  // the valve spring pushes it back with P + k q + k3 q³.
  void force(double, const double* q, const double* v, double* r) const override {
    const double stem = k_s * (q[0] - q[1]) + c_s * (v[0] - v[1]);
    r[0] = -stem;
    r[1] = stem - (P + k * q[1] + k3 * q[1] * q[1] * q[1]);
  }
  void solve_mass(const double* b, double* x) const override {  // M = diag(m_t, m_v)
    x[0] = b[0] / m_t;
    x[1] = b[1] / m_v;
  }
  // Energies: the history's energy columns and their balance.
  double kinetic_energy(const double* v) const override { return 0.5 * (m_t * v[0] * v[0] + m_v * v[1] * v[1]); }
  double potential_energy(const double* q) const override {
    const double d = q[0] - q[1];
    return 0.5 * k_s * d * d + P * q[1] + 0.5 * k * q[1] * q[1] + 0.25 * k3 * q[1] * q[1] * q[1] * q[1];
  }
  double damping_power(const double* v) const override { return c_s * (v[0] - v[1]) * (v[0] - v[1]); }
  std::string name() const override { return "tappet + valve, progressive spring (C++)"; }
};

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: own_follower SCENE.toml OUT_DIR [SPEED_REV_S]\n");
    return 2;
  }
  try {
    camdyn::Scene scene = camdyn::load_scene_file(argv[1]);
    if (argc > 3) camdyn::apply_override(scene, std::string("cam.speed_rev_s=") + argv[3]);
    camdyn::Simulator sim(scene, std::make_shared<TappetValve>());
    camdyn::ensure_output_dir(argv[2]);
    camdyn::StreamingHistoryWriter writer(argv[2], sim.extra_columns());
    const camdyn::Summary s = sim.run(&writer);
    writer.finish();
    std::printf("%s\n", s.BriefReport().c_str());
    return s.finished ? 0 : 1;
  } catch (const camdyn::SceneError& e) {  // bad scene or bad follower (file "<follower>")
    std::fprintf(stderr, "bad input: %s\n", e.what());
    return 2;
  }
}
