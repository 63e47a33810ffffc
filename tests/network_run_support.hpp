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
