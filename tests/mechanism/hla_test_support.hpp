// The test scene the hydraulic lash adjuster's tests share: a plunger of `mass` on an HLA to
// ground, pushed down by a constant load (a spring [plunger, ground] of stiffness 0 and
// preload `load`), a stop `lash` above it; rtol 1e-10, atol 1e-15, element forces on.
#pragma once

#include "camdyn/simulator.hpp"

namespace camdyn_test {

/// One classic RK4 step of ẏ = f(y) (N unknowns; f(const double* y, double* ẏ)) of size h,
/// in place: the tests' own integration of the element's equations.
template <int N, class F>
void rk4_step(const F& f, double (&y)[N], double h) {
  double k1[N], k2[N], k3[N], k4[N], z[N];
  f(y, k1);
  for (int j = 0; j < N; ++j) z[j] = y[j] + 0.5 * h * k1[j];
  f(z, k2);
  for (int j = 0; j < N; ++j) z[j] = y[j] + 0.5 * h * k2[j];
  f(z, k3);
  for (int j = 0; j < N; ++j) z[j] = y[j] + h * k3[j];
  f(z, k4);
  for (int j = 0; j < N; ++j) y[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
}

inline camdyn::Scene hla_plunger_scene(const camdyn::ElementSpec& e, double mass, double load, double lash,
                                       camdyn::Integrator integ, camdyn::ContactModel model) {
  using namespace camdyn;
  Scene s = default_scene();
  s.title = "hla";
  s.follower.kind = FollowerKind::Network;
  NodeSpec n;
  n.name = "plunger";
  n.mass = mass;
  s.network.nodes = {n};
  ElementSpec ld;
  ld.name = "load";
  ld.kind = ElementKind::Spring;
  ld.nodes = {"plunger", "ground"};
  ld.stiffness = 0.0;
  ld.preload = load;
  s.network.elements = {e, ld};
  ContactPointSpec stop;
  stop.name = "stop";
  stop.kind = ContactPointKind::Stop;
  stop.nodes = {"plunger"};
  stop.side = StopSide::Above;
  stop.clearance = lash;
  s.network.contacts = {stop};
  s.contact.model = model;
  s.solver.integrator = integ;
  s.solver.rtol = 1e-10;
  s.solver.atol = 1e-15;
  s.run.element_forces = true;
  return s;
}

}  // namespace camdyn_test
