// camdyn as a library (README "Use as a library"): a scene built in code, an override as
// on the command line, the closed-form jump speed, a run with an observer, the summary.
//
//   Build against an installed camdyn:  cmake -S examples/library -B build-lib && cmake --build build-lib
//   or with pkg-config:                 c++ main.cpp $(pkg-config --cflags --libs camdyn)
#include <camdyn/camdyn.hpp>  // the whole API: Scene, Simulator, Observer, Summary, jump_speed

#include <cmath>
#include <cstdio>

// Receives rows and events as they are computed.
struct Watch : camdyn::Observer {
  long rows = 0;
  double max_force = 0;
  void on_row(const camdyn::HistoryRow& r) override {
    ++rows;
    max_force = std::fmax(max_force, r.contact_force);
  }
  void on_event(const camdyn::ContactEvent& e) override {
    if (e.type == camdyn::EventKind::Separation)
      std::printf("  separation at t = %.6f s, cam angle %.2f deg\n", e.t,
                  std::fmod(e.theta * 180 / M_PI, 360.0));
  }
};

int main() {
  camdyn::Scene scene;  // every field has a default (scene.hpp): a rigid follower of mass 1
  scene.title = "eccentric circle cam above its jump speed";
  scene.cam.profile = camdyn::CamProfileKind::Circle;
  scene.cam.radius = 2.0;        // R
  scene.cam.eccentricity = 0.5;  // e: lift X_C = R + e cos θ
  scene.cam.speed_rev_s = 15.0;
  scene.run.t_end = 0.2;
  try {
    camdyn::apply_override(scene, "spring.precompression=7");  // as `--set`, validated
    // Rigid follower: the jump speed has a closed form, √(k δ₀ / (m e)) / 2π.
    const camdyn::JumpResult jump = camdyn::jump_speed(scene);
    const double exact = std::sqrt(500.0 * 7.0 / (1.0 * 0.5)) / (2 * M_PI);
    std::printf("jump speed %.9f rev/s (%s; closed form %.9f)\n", jump.jump_speed_rev_s,
                jump.method.c_str(), exact);

    camdyn::Simulator sim(scene);
    Watch watch;
    const camdyn::Summary s = sim.run(&watch);
    std::printf("%s\n", s.BriefReport().c_str());
    std::printf("%ld rows, max contact force %.6g\n", watch.rows, watch.max_force);
    const bool ok = s.finished && s.separations > 0 &&
                    std::abs(jump.jump_speed_rev_s - exact) < 1e-9 * exact;
    return ok ? 0 : 1;
  } catch (const camdyn::SceneError& e) {  // bad input: file, key, value and rule
    std::fprintf(stderr, "bad scene: %s\n", e.what());
    return 2;
  }
}
