// A network (or any) scene run with every history row kept and its extra column names, for
// the tests that read per-contact and per-node columns (test_network.cpp,
// test_network_event_held.cpp).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "camdyn/simulator.hpp"

namespace camdyn_test {

/// The simplest direct-acting valve train (issue 28): one node "valve" of `mass` on a
/// "valve_spring" to ground (`stiffness`, `preload`), a cam contact "cam" above it with
/// `clearance` and a seat "seat" (stop, below) — two contacts on one node.
inline camdyn::NetworkSpec one_node_valve_network(double mass, double stiffness, double preload,
                                                  double clearance) {
  using namespace camdyn;
  NetworkSpec n;
  NodeSpec v;
  v.name = "valve";
  v.mass = mass;
  n.nodes = {v};
  ElementSpec sp;
  sp.name = "valve_spring";
  sp.kind = ElementKind::Spring;
  sp.nodes = {"valve", "ground"};
  sp.stiffness = stiffness;
  sp.preload = preload;
  n.elements = {sp};
  ContactPointSpec cam;
  cam.name = "cam";
  cam.kind = ContactPointKind::Cam;
  cam.nodes = {"valve"};
  cam.clearance = clearance;
  ContactPointSpec seat;
  seat.name = "seat";
  seat.kind = ContactPointKind::Stop;
  seat.nodes = {"valve"};
  seat.side = StopSide::Below;
  n.contacts = {cam, seat};
  return n;
}

struct NetRun {
  camdyn::Summary sum;
  std::vector<camdyn::HistoryRow> rows;
  std::vector<std::string> cols;
  double col(const camdyn::HistoryRow& r, const std::string& name) const {
    for (size_t i = 0; i < cols.size(); ++i)
      if (cols[i] == name) return r.extra[i];
    ADD_FAILURE() << "no column " << name;
    return NAN;
  }
};

// The two-mass valve train of the tests (issue 23): the OHC example without the valve
// spring's coil masses (tappet 45 g, stem 5e7 N/m, valve 50 g, valve spring 35 N/mm with
// 250 N preload, 0.2 mm lash at the cam, seat), event method, one camshaft revolution.
inline camdyn::Scene two_mass_train() {
  camdyn::Scene s = camdyn::load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_bucket_tappet.toml");
  for (camdyn::ElementSpec& e : s.network.elements)
    if (e.name == "valve_spring") {
      e.masses = 0;
      e.mass = 0.0;
    }
  s.contact.model = camdyn::ContactModel::Event;
  s.run.t_end = 0.04;  // one camshaft revolution at 25 rev/s
  return s;
}

inline NetRun run_keeping_rows(const camdyn::Scene& s) {
  struct Keep : camdyn::Observer {
    std::vector<camdyn::HistoryRow>* rows;
    void on_row(const camdyn::HistoryRow& r) override { rows->push_back(r); }
  } keep;
  NetRun r;
  keep.rows = &r.rows;
  camdyn::Simulator sim(s);
  r.cols = sim.extra_columns();
  r.sum = sim.run(&keep);
  return r;
}

}  // namespace camdyn_test
