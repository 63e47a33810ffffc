// Downstream example: links the *installed* camdyn through find_package(camdyn).
//
//   Eccentric circle cam (radius R, eccentricity e): X_C(θ) = e cos θ + R exactly.
//   The program checks camdyn's contact point against that closed form, then runs the
//   paper's case A (rigid follower) for a short time and prints the brief report.
#include <camdyn/camdyn.hpp>

#include <cmath>
#include <cstdio>

int main() {
  camdyn::CamSpec spec;
  spec.profile = camdyn::CamProfileKind::Circle;
  spec.radius = 2.0;
  spec.eccentricity = 0.5;
  camdyn::Cam cam(spec);
  for (int i = 0; i < 360; ++i) {
    const double th = i * M_PI / 180.0;
    const double err = std::abs(cam.evaluate(th).X_C - (0.5 * std::cos(th) + 2.0));
    if (err > 1e-12) {
      std::printf("circle cam mismatch at %d deg: %g\n", i, err);
      return 1;
    }
  }
  camdyn::Scene scene = camdyn::paper_case("A");
  scene.run.t_end = 0.05;
  camdyn::Simulator sim(scene);
  const camdyn::Summary s = sim.run();
  std::printf("%s\n", s.BriefReport().c_str());
  return s.finished ? 0 : 1;
}
