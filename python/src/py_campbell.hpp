// camdyn._camdyn — the Campbell diagram for Python's camdyn.campbell (camdyn_module.cpp):
// options from a dict (unknown names refused), the diagram as a dict of lists.
#pragma once

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "camdyn/campbell.hpp"

namespace camdyn_py {

namespace py = pybind11;

inline py::dict campbell_dict(const camdyn::Scene& sc, const py::dict& options) {
  using namespace camdyn;
  CampbellOptions o;
  for (const auto& item : options) {
    const std::string k = py::str(item.first);
    if (k == "column") o.column = item.second.cast<std::string>();
    else if (k == "speeds_rev_s") o.speeds_rev_s = item.second.cast<std::vector<double>>();
    else if (k == "settle_revolutions") o.settle_revolutions = item.second.cast<int>();
    else if (k == "revolutions") o.revolutions = item.second.cast<int>();
    else if (k == "samples_per_revolution") o.samples_per_revolution = item.second.cast<int>();
    else if (k == "max_order") o.max_order = item.second.cast<double>();
    else if (k == "threads") o.threads = item.second.cast<int>();
    else
      throw SceneError("campbell", 0, k, py::str(item.second),
                       "unknown option; allowed: column, speeds_rev_s, settle_revolutions, revolutions, "
                       "samples_per_revolution, max_order, threads");
  }
  CampbellDiagram d;
  {
    py::gil_scoped_release nogil;
    d = campbell(sc, o);
  }
  py::dict r;
  r["column"] = d.column;
  r["speed_rev_s"] = d.speed_rev_s;
  r["order"] = d.order;
  r["amplitude"] = d.amplitude;
  py::list lines;
  for (const CampbellLine& l : d.lines) {
    py::dict x;
    x["name"] = l.name;
    x["frequency_hz"] = l.frequency_hz;
    lines.append(x);
  }
  r["lines"] = lines;
  return r;
}

}  // namespace camdyn_py
