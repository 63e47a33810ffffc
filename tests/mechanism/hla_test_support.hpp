// The test scene the hydraulic lash adjuster's tests share: a plunger of `mass` on an HLA to
// ground, pushed down by a constant load (a spring [plunger, ground] of stiffness 0 and
// preload `load`), a stop `lash` above it; rtol 1e-10, atol 1e-15, element forces on.
#pragma once

#include "camdyn/simulator.hpp"

namespace camdyn_test {

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
