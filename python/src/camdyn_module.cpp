// camdyn._camdyn — the compiled part of the Python package `camdyn`.
//
// A thin layer over the C++ library: scenes come in as (kind, text, source, overrides) —
// a file path, TOML text or the built-in default, plus "dotted.key=value" overrides — and
// go through exactly the CLI's path (load_scene_file / parse_scene, apply_overrides, the
// cam check, resolve_defaults, validate), so errors carry the CLI's message. The Python
// side (python/camdyn/__init__.py) turns dicts into TOML, keyword overrides into
// assignments, and the summary JSON text into a dict.
//
// Threads: the GIL is released while C++ integrates and reacquired only to call a Python
// observer and to poll for signals (PyErr_CheckSignals, every row with an observer and in
// the ~0.2 s progress callback), so Ctrl-C stops a run and raises KeyboardInterrupt.
//
// Bring your own follower (run_follower): a Python follower object, normalised by the
// Python side into a spec dict, runs as PyFollower (py_follower.hpp) — a
// camdyn::FollowerSystem that holds the Python callables and takes the GIL in every callback. A Python exception in a
// callback is kept (with its text), the callback throws a C++ exception (which the engine
// catches and turns into a failed step; every later callback throws at once without
// calling Python) and the run's summary says finished = false, termination "error",
// message "at t = T: Python follower: force(t, q, v) raised ValueError: ...".
// KeyboardInterrupt / SystemExit (not Exception subclasses) are re-raised instead.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <future>
#include <cstring>
#include <stdexcept>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include <csignal>
#include <signal.h>

#include "camdyn/cam.hpp"
#include "camdyn/designer.hpp"
#include "camdyn/follower_system.hpp"
#include "camdyn/spectrum.hpp"
#include "camdyn/initial_state.hpp"
#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "py_campbell.hpp"
#include "py_follower.hpp"

#ifndef CAMDYN_VERSION
#define CAMDYN_VERSION "unknown"
#endif

namespace py = pybind11;
using namespace camdyn;
using camdyn_python::CubicSpringFollower;
using camdyn_python::fmt_g;
using camdyn_python::PyFollower;

namespace {

/// The scene a call works on, built as the CLI's build_scene() does (src/cli/main.cpp):
/// kind "file" (text = path), "toml" (text = TOML, named `source` in messages) or
/// "default" (the built-in scene, paper case B2); then the overrides, validated once.
/// @throws SceneError with the CLI's message.
ValidatedScene build_validated(const std::string& kind, const std::string& text, const std::string& source,
                               const std::vector<std::string>& overrides) {
  // The file (or text) with the overrides set in it, validated once (as the CLI).
  if (kind != "file" && kind != "toml" && kind != "default")
    throw std::invalid_argument("camdyn._camdyn: unknown scene kind '" + kind + "'");
  ValidatedScene sc = kind == "file"   ? load_validated_scene(text, overrides)
                      : kind == "toml" ? parse_validated_scene(text, source, overrides)
                                       : validated(default_scene(), overrides);
  // Cam geometry is checked by the Cam itself; name the scene or --set, as the CLI does.
  try {
    const Cam cam(sc->cam);
  } catch (const SceneError& e) {
    if (e.file() != "<cam>") throw;
    bool from_set = false;
    for (const auto& s : overrides)
      if (s.rfind("cam.", 0) == 0) from_set = true;
    throw SceneError(from_set ? std::string("--set") : sc->source, 0, e.key(), e.value(),
                     e.rule());
  }
  return sc;
}
Scene build_scene(const std::string& kind, const std::string& text, const std::string& source,
                  const std::vector<std::string>& overrides) {
  return build_validated(kind, text, source, overrides).scene();
}

/// While it lives, in Python's main thread with Python's default SIGINT handler in place:
/// SIGINT sets `stop` at once (the run stops after the engine's current step, whatever the
/// engine, without waiting for an observer or progress callback) and is remembered;
/// Python's handler is restored afterwards (the caller raises KeyboardInterrupt).
class StopOnSigint {
 public:
  explicit StopOnSigint(std::atomic<bool>* stop) {
    py::module_ signal = py::module_::import("signal"), threading = py::module_::import("threading");
    if (!threading.attr("current_thread")().is(threading.attr("main_thread")())) return;
    if (!signal.attr("getsignal")(signal.attr("SIGINT")).is(signal.attr("default_int_handler"))) return;
    target().store(stop);
    seen_flag().store(false);
    struct sigaction sa {};
    sa.sa_handler = &StopOnSigint::on_signal;
    sigemptyset(&sa.sa_mask);
    installed_ = sigaction(SIGINT, &sa, &old_) == 0;
  }
  ~StopOnSigint() {
    if (installed_) sigaction(SIGINT, &old_, nullptr);
    target().store(nullptr);
  }
  StopOnSigint(const StopOnSigint&) = delete;
  StopOnSigint& operator=(const StopOnSigint&) = delete;
  bool seen() const { return installed_ && seen_flag().load(); }

 private:
  static std::atomic<std::atomic<bool>*>& target() {
    static std::atomic<std::atomic<bool>*> t{nullptr};
    return t;
  }
  static std::atomic<bool>& seen_flag() {
    static std::atomic<bool> s{false};
    return s;
  }
  static void on_signal(int) {
    if (std::atomic<bool>* t = target().load()) t->store(true);
    seen_flag().store(true);
  }
  struct sigaction old_ {};
  bool installed_ = false;
};

/// The Simulator of a scene; model-building failures become SceneError as in the CLI.
std::unique_ptr<Simulator> make_simulator(const ValidatedScene& sc) {
  try {
    return std::make_unique<Simulator>(sc);
  } catch (const SceneError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(sc->source, 0, "scene", sc->title,
                     std::string("cannot build the model: ") + e.what());
  }
}

/// The values of one history row in history_columns() order.
void row_values(const HistoryRow& r, double* v) {
  v[0] = r.t;
  v[1] = r.theta;
  v[2] = r.u_c;
  v[3] = r.v_c;
  v[4] = r.a_c;
  v[5] = r.contact_force;
  v[6] = r.gap;
  v[7] = double(r.in_contact);
  v[8] = r.kinetic;
  v[9] = r.potential;
  v[10] = r.work_cam;
  v[11] = r.dissipated;
}
constexpr std::size_t kColumns = 12;

/// Keeps every row; calls the Python observer (GIL taken) for each one; polls signals.
/// The observer's dict has the history_columns(), then (network scenes, user followers) the
/// `extra` columns (Simulator::extra_columns()).
class PyObserver : public Observer {
 public:
  PyObserver(py::object callback, std::atomic<bool>* stop, const std::vector<std::string>& extra)
      : callback_(std::move(callback)), stop_(stop) {
    if (!callback_.is_none()) {
      for (const auto& c : history_columns()) keys_.emplace_back(py::str(c));
      for (const auto& c : extra) keys_.emplace_back(py::str(c));
    }
  }
  ~PyObserver() override {
    py::gil_scoped_acquire gil;  // py::object members are released under the GIL
    keys_.clear();
    callback_ = py::object();
    pending_.reset();
  }

  void on_row(const HistoryRow& r) override {
    rows_.push_back(r);
    if (callback_.is_none() || pending_) return;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) return fail();
    try {
      double v[kColumns];
      row_values(r, v);
      py::dict d;
      for (std::size_t i = 0; i < kColumns; ++i) d[keys_[i]] = py::float_(v[i]);
      for (std::size_t i = kColumns; i < keys_.size(); ++i)
        d[keys_[i]] = py::float_(i - kColumns < r.extra.size() ? r.extra[i - kColumns] : NAN);
      const py::object res = callback_(d);
      if (res.ptr() == Py_False) stop_->store(true);  // "return False" stops the run
    } catch (py::error_already_set& e) {
      e.restore();
      fail();
    }
  }

  void on_progress(double, double, long) override {
    if (pending_) return;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) fail();
  }

  const std::vector<HistoryRow>& rows() const { return rows_; }
  /// Re-raise a Python exception caught during the run (KeyboardInterrupt, or one raised
  /// by the observer). Call with the GIL held.
  void rethrow_pending() {
    if (pending_) {
      std::unique_ptr<py::error_already_set> p = std::move(pending_);
      throw py::error_already_set(std::move(*p));
    }
  }

 private:
  // With the GIL held and a Python error set: keep it for later and stop the run.
  void fail() {
    pending_ = std::make_unique<py::error_already_set>();  // fetches and clears the error
    stop_->store(true);
  }

  py::object callback_;
  std::atomic<bool>* stop_;
  std::vector<py::str> keys_;
  std::vector<HistoryRow> rows_;
  std::unique_ptr<py::error_already_set> pending_;
};

/// run(): (summary JSON text, {column: float64 array}, [event dicts]). Network scenes and
/// user followers: the history has the extra columns (F_<contact>, gap_<contact>,
/// in_<contact>, u_<node>, v_<node>) after the standard ones, and each event dict has
/// "contact".
/// With a user's follower (`follower`: a FollowerSystem made in C++, or the spec dict of a
/// Python follower, camdyn._follower_spec()), the scene's follower is replaced by it.
py::tuple run_scene(const std::string& kind, const std::string& text, const std::string& source,
                    const std::vector<std::string>& overrides, py::object observer,
                    const py::object& follower) {
  const ValidatedScene valid = build_validated(kind, text, source, overrides);
  const Scene& sc = valid.scene();
  std::unique_ptr<Simulator> sim;
  std::shared_ptr<PyFollower> pyf;
  if (follower.is_none()) {
    sim = make_simulator(valid);
  } else {
    std::shared_ptr<const FollowerSystem> fs;
    if (py::isinstance<FollowerSystem>(follower)) {
      fs = follower.cast<std::shared_ptr<FollowerSystem>>();
    } else {
      pyf = std::make_shared<PyFollower>(follower.cast<py::dict>());
      fs = pyf;
    }
    try {
      sim = std::make_unique<Simulator>(valid, fs);  // checks the follower (SceneError "<follower>")
    } catch (const SceneError&) {
      throw;
    } catch (const std::exception& e) {
      // a callback raised while the model was built (before any run): raise it as is
      if (pyf && pyf->has_pending()) pyf->rethrow();
      if (pyf && pyf->failed())  // a bad return value
        throw SceneError("<follower>", 0, "follower", fs->name(), pyf->error());
      throw SceneError("<follower>", 0, "follower", fs->name(), std::string("cannot build the model: ") + e.what());
    }
  }
  std::atomic<bool> stop{false};
  if (pyf) pyf->set_stop(&stop);
  const std::vector<std::string>& extra = sim->extra_columns();
  PyObserver obs(std::move(observer), &stop, extra);
  Summary summary;
  bool interrupted = false;
  {
    StopOnSigint ctrl_c(&stop);  // Ctrl-C stops any engine after its current step
    {
      py::gil_scoped_release nogil;
      try {
        summary = sim->run(&obs, &stop, "stopped by caller");
      } catch (const std::exception& e) {  // as the CLI: keep what was computed
        summary = Summary{};
        summary.finished = false;
        summary.message = std::string("internal error: ") + e.what();
        summary.t_end = obs.rows().empty() ? 0.0 : obs.rows().back().t;
      }
    }
    interrupted = ctrl_c.seen();
  }
  if (pyf) pyf->set_stop(nullptr);
  if (interrupted) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  if (summary.scene.empty()) summary.scene = sc.title;
  obs.rethrow_pending();
  if (pyf && pyf->failed()) {
    // A Python callback raised: the run ended at the step that called it (the engine saw a
    // failed callback, or the stop flag). Report the Python error, not its consequence
    // (a SUNDIALS flag, a step size underflow after Lee's retries, "stopped by caller").
    if (pyf->must_reraise()) pyf->rethrow();  // KeyboardInterrupt, SystemExit
    summary.finished = false;
    summary.termination = Termination::Error;
    summary.message = "at t = " + fmt_g(summary.t_end) + ": " + pyf->error();
  }

  const auto& rows = obs.rows();
  const auto n = static_cast<py::ssize_t>(rows.size());
  std::vector<py::array_t<double>> cols;
  std::vector<double*> ptr;
  for (std::size_t c = 0; c < kColumns; ++c) {
    cols.emplace_back(n);
    ptr.push_back(cols.back().mutable_data());
  }
  double v[kColumns];
  for (py::ssize_t i = 0; i < n; ++i) {
    row_values(rows[static_cast<std::size_t>(i)], v);
    for (std::size_t c = 0; c < kColumns; ++c) ptr[c][i] = v[c];
  }
  py::dict history;
  for (std::size_t c = 0; c < kColumns; ++c) history[py::str(history_columns()[c])] = cols[c];
  for (std::size_t c = 0; c < extra.size(); ++c) {
    py::array_t<double> col(n);
    double* p = col.mutable_data();
    for (py::ssize_t i = 0; i < n; ++i) {
      const auto& x = rows[static_cast<std::size_t>(i)].extra;
      p[i] = c < x.size() ? x[c] : NAN;
    }
    history[py::str(extra[c])] = col;
  }

  const bool named_contacts = has_named_contacts(extra);
  py::list events;
  for (const auto& e : summary.events) {
    py::dict d;
    d["t"] = e.t;
    d["kind"] = to_string(e.type);
    d["impact_velocity"] = e.impact_velocity;
    d["theta"] = e.theta;
    d["impulse"] = e.impulse;
    if (named_contacts) d["contact"] = e.contact;  // networks and user followers (as events.csv)
    events.append(d);
  }
  return py::make_tuple(summary_json(summary, sc), history, events);
}

py::dict jump(const std::string& kind, const std::string& text, const std::string& source,
              const std::vector<std::string>& overrides, const py::dict& options, const py::object& follower) {
  const Scene sc = build_scene(kind, text, source, overrides);
  // A user follower: a C++ FollowerSystem, or a Python one's spec dict.
  std::shared_ptr<const FollowerSystem> fs;
  std::shared_ptr<PyFollower> pyf;
  if (!follower.is_none()) {
    if (py::isinstance<FollowerSystem>(follower)) {
      fs = follower.cast<std::shared_ptr<FollowerSystem>>();
    } else {
      pyf = std::make_shared<PyFollower>(follower.cast<py::dict>());
      fs = pyf;
    }
  }
  JumpOptions jo;
  for (const auto& item : options) {
    const std::string k = py::str(item.first);
    if (k == "scan_points") jo.scan_points = item.second.cast<int>();
    else if (k == "rel_tol") jo.rel_tol = item.second.cast<double>();
    else if (k == "lo_rev_s") jo.lo_rev_s = item.second.cast<double>();
    else if (k == "hi_rev_s") jo.hi_rev_s = item.second.cast<double>();
    else if (k == "force_simulation") jo.force_simulation = item.second.cast<bool>();
    else if (k == "grid_points") jo.grid_points = item.second.cast<int>();
    else if (k == "jobs") jo.jobs = item.second.cast<int>();
    else
      throw SceneError("jump_speed", 0, k, py::str(item.second),
                       "unknown option; allowed: scan_points, rel_tol, lo_rev_s, hi_rev_s, "
                       "force_simulation, grid_points, jobs");
  }
  if (pyf) jo.jobs = 1;  // a Python follower's callbacks hold the interpreter: one thread
  jo.validate();
  JumpResult r;
  try {
    py::gil_scoped_release nogil;
    r = fs ? jump_speed(sc, fs, jo) : jump_speed(sc, jo);
  } catch (const std::exception&) {
    // a Python callback raised: raise its exception, not its consequence
    if (pyf && pyf->has_pending()) pyf->rethrow();
    if (pyf && pyf->failed()) throw SceneError("<follower>", 0, "follower", fs->name(), pyf->error());
    throw;
  }
  py::dict d;
  d["jump_speed_rev_s"] = r.jump_speed_rev_s;
  d["method"] = r.method;
  d["theta_deg"] = r.theta_deg;
  d["lo_rev_s"] = r.lo_rev_s;
  d["hi_rev_s"] = r.hi_rev_s;
  d["simulations"] = r.simulations;
  d["phenomenon"] = r.phenomenon;
  d["phenomenon_text"] = r.phenomenon_text;
  if (r.method == "simulation") {
    d["grid_simulations"] = r.grid_simulations;
    d["failed_simulations"] = r.failed_simulations;
    d["range_lo_rev_s"] = r.range_lo_rev_s;
    d["range_hi_rev_s"] = r.range_hi_rev_s;
    d["grid_spacing_rev_s"] = r.grid_spacing_rev_s;
    d["monotone"] = r.monotone;
    d["monotone_text"] = r.monotone_text;
    py::list bands, trials;
    for (const SpeedBand& b : r.bands) {
      py::dict x;
      x["kind"] = b.kind;
      x["contact"] = b.contact;
      x["theta_deg"] = b.theta_deg;
      x["from_out_rev_s"] = b.from_out;
      x["from_in_rev_s"] = b.from_in;
      x["to_in_rev_s"] = b.to_in;
      x["to_out_rev_s"] = b.to_out;
      bands.append(x);
    }
    for (const SpeedTrial& t : r.trials) {
      py::dict x;
      x["speed_rev_s"] = t.speed_rev_s;
      x["finished"] = t.finished;
      x["kinds"] = t.kinds;
      x["text"] = t.text;
      trials.append(x);
    }
    d["bands"] = bands;
    d["trials"] = trials;
    d["text"] = speed_map_text(r);
  }
  return d;
}

py::tuple cam_motion(const std::string& kind, const std::string& text, const std::string& source,
                     const std::vector<std::string>& overrides,
                     const py::array_t<double, py::array::c_style | py::array::forcecast>& t, bool lift) {
  const Scene sc = build_scene(kind, text, source, overrides);
  const Cam cam(sc.cam);
  const CamDrive drive(sc.cam);
  const double base = lift ? cam_lift_base(cam, sc.cam) : 0.0;  // lift: X_C − X_base
  const auto n = t.size();
  py::array_t<double> X(n), Xd(n), Xdd(n);
  const double* tp = t.data();
  double *x = X.mutable_data(), *xd = Xd.mutable_data(), *xdd = Xdd.mutable_data();
  for (py::ssize_t i = 0; i < n; ++i) {
    const CamMotion m = cam.motion(drive.theta(tp[i]), drive.omega(tp[i]), drive.omega_dot(tp[i]));
    x[i] = m.X - base;
    xd[i] = m.Xdot;
    xdd[i] = m.Xddot;
  }
  return py::make_tuple(X, Xd, Xdd);
}

/// initial_state_on_cam(): a user follower (spec dict or C++ FollowerSystem) put on the cam
/// at t = 0 (include/camdyn/initial_state.hpp); returns (q0, v0) as arrays.
py::tuple on_cam(const std::string& kind, const std::string& text, const std::string& source,
                 const std::vector<std::string>& overrides, const py::object& follower) {
  const Scene sc = build_scene(kind, text, source, overrides);
  std::shared_ptr<const FollowerSystem> fs;
  if (py::isinstance<FollowerSystem>(follower))
    fs = follower.cast<std::shared_ptr<FollowerSystem>>();
  else
    fs = std::make_shared<PyFollower>(follower.cast<py::dict>());
  const FollowerStart s = initial_state_on_cam(sc, *fs);
  return py::make_tuple(py::array_t<double>(py::ssize_t(s.q.size()), s.q.data()),
                        py::array_t<double>(py::ssize_t(s.v.size()), s.v.data()));
}

/// run_batch(): scenes given as (kind, text, source, overrides) tuples, all built (and
/// checked) first; then run `threads` at a time in C++ threads while this thread, holding
/// the GIL only briefly, polls for Ctrl-C every 0.1 s. Returns the summary JSON texts.
std::vector<std::string> batch(const std::vector<std::tuple<std::string, std::string, std::string,
                                                            std::vector<std::string>>>& specs,
                               int threads) {
  std::vector<ValidatedScene> scenes;  // validated once here, not again by the runs
  scenes.reserve(specs.size());
  for (const auto& [kind, text, source, overrides] : specs)
    scenes.push_back(build_validated(kind, text, source, overrides));
  std::atomic<bool> stop{false};
  std::vector<Summary> sums;
  {
    py::gil_scoped_release nogil;
    auto fut = std::async(std::launch::async,
                          [&] { return run_batch(scenes, threads, {}, &stop); });
    while (fut.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) {
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {
        stop.store(true);
        py::error_already_set err;  // KeyboardInterrupt: wait for the workers, then raise
        {
          py::gil_scoped_release again;
          fut.wait();
        }
        throw err;
      }
    }
    sums = fut.get();
  }
  std::vector<std::string> out;
  out.reserve(sums.size());
  for (std::size_t i = 0; i < sums.size(); ++i) {
    if (sums[i].scene.empty()) sums[i].scene = scenes[i]->title;
    out.push_back(summary_json(sums[i], scenes[i].scene()));
  }
  return out;
}

}  // namespace

PYBIND11_MODULE(_camdyn, m) {
  m.doc() = "camdyn: cam-follower dynamics (compiled part; use the package `camdyn`)";
  m.attr("__version__") = CAMDYN_VERSION;

  static py::exception<SceneError> scene_error(m, "SceneError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneError& e) {
      // The CLI's message (what() after "camdyn: "), plus its parts as attributes.
      py::object type = py::reinterpret_borrow<py::object>(scene_error);
      py::object inst = type(py::str(e.what()));
      inst.attr("file") = e.file();
      inst.attr("line") = e.line();
      inst.attr("key") = e.key();
      inst.attr("value") = e.value();
      inst.attr("rule") = e.rule();
      PyErr_SetObject(scene_error.ptr(), inst.ptr());
    }
  });

  m.def("history_columns", &history_columns, "History column names, in order.");
  // The checks `camdyn scene` makes, which are those of a run's start (make_simulator).
  m.def("resolved_scene",
        [](const std::string& kind, const std::string& text, const std::string& source,
           const std::vector<std::string>& overrides) {
          const ValidatedScene sc = build_validated(kind, text, source, overrides);
          make_simulator(sc);
          return to_toml(sc.scene());
        },
        py::arg("kind"), py::arg("text"), py::arg("source"), py::arg("overrides"));
  // The scene's keys only (a base whose arrays an override replaces: it may not run alone).
  m.def("scene_toml",
        [](const std::string& kind, const std::string& text, const std::string& source,
           const std::vector<std::string>& overrides) {
          return to_toml(build_scene(kind, text, source, overrides));
        },
        py::arg("kind"), py::arg("text"), py::arg("source"), py::arg("overrides"));
  m.def("run", &run_scene, py::arg("kind"), py::arg("text"), py::arg("source"),
        py::arg("overrides"), py::arg("observer"), py::arg("follower") = py::none());
  // Followers written in C++ (opaque; pass as camdyn.run(..., follower=...)).
  py::class_<FollowerSystem, std::shared_ptr<FollowerSystem>>(m, "FollowerSystem")
      .def_property_readonly("name", &FollowerSystem::name)
      .def_property_readonly("size", &FollowerSystem::size);
  py::class_<CubicSpringFollower, FollowerSystem, std::shared_ptr<CubicSpringFollower>>(
      m, "CubicSpringFollower",
      "The cubic hardening valve spring follower of tests/mechanism/test_follower_system.cpp, in C++ "
      "(r = -(P + k q + k3 q^3), M = m): the native reference for timing Python followers.")
      .def(py::init<double, double, double, double>(), py::arg("m"), py::arg("k"), py::arg("k3"),
           py::arg("P"));
  m.def("jump_speed", &jump, py::arg("kind"), py::arg("text"), py::arg("source"),
        py::arg("overrides"), py::arg("options"), py::arg("follower") = py::none());
  m.def("run_batch", &batch, py::arg("specs"), py::arg("threads"));
  m.def(
      "order_spectrum",
      [](const std::vector<double>& theta, const std::vector<double>& y, int revolutions, int samples,
         double max_order) {
        SpectrumOptions o;
        o.revolutions = revolutions;
        o.samples_per_revolution = samples;
        o.max_order = max_order;
        const OrderSpectrum s = order_spectrum(theta, y, o);
        py::dict d;
        d["order"] = s.order;
        d["amplitude"] = s.amplitude;
        d["phase_deg"] = s.phase_deg;
        d["revolutions"] = s.revolutions;
        return d;
      },
      py::arg("theta"), py::arg("y"), py::arg("revolutions") = 0, py::arg("samples_per_revolution") = 1024,
      py::arg("max_order") = 64.0);
  m.def("campbell", [](const std::string& kind, const std::string& text, const std::string& source,
                       const std::vector<std::string>& overrides, const py::dict& options) {
    return camdyn_py::campbell_dict(build_scene(kind, text, source, overrides), options);
  });
  m.def("cam_motion", &cam_motion, py::arg("kind"), py::arg("text"), py::arg("source"),
        py::arg("overrides"), py::arg("t"), py::arg("lift") = false);
  m.def("initial_state_on_cam", &on_cam, py::arg("kind"), py::arg("text"), py::arg("source"),
        py::arg("overrides"), py::arg("follower"));
}
