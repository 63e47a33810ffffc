// camdyn._camdyn — the compiled part of the Python package `camdyn` (issue 17).
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
// Python side into a spec dict, runs as PyFollower — a camdyn::FollowerSystem that holds
// the Python callables and takes the GIL in every callback. A Python exception in a
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

#include "camdyn/cam.hpp"
#include "camdyn/designer.hpp"
#include "camdyn/follower_system.hpp"
#include "camdyn/spectrum.hpp"
#include "camdyn/initial_state.hpp"
#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

#ifndef CAMDYN_VERSION
#define CAMDYN_VERSION "unknown"
#endif

namespace py = pybind11;
using namespace camdyn;

namespace {

/// The scene a call works on, built as the CLI's build_scene() does (src/cli/main.cpp):
/// kind "file" (text = path), "toml" (text = TOML, named `source` in messages) or
/// "default" (the built-in scene, paper case B2); then the overrides, validated once.
/// @throws SceneError with the CLI's message.
Scene build_scene(const std::string& kind, const std::string& text, const std::string& source,
                  const std::vector<std::string>& overrides) {
  Scene sc;
  if (kind == "file") {
    sc = load_scene_file(text);
  } else if (kind == "toml") {
    sc = parse_scene(text, source);
  } else if (kind == "default") {
    sc = default_scene();
  } else {
    throw std::invalid_argument("camdyn._camdyn: unknown scene kind '" + kind + "'");
  }
  apply_overrides(sc, overrides);
  // Cam geometry is checked by the Cam itself; name the scene or --set, as the CLI does.
  try {
    const Cam cam(sc.cam);
  } catch (const SceneError& e) {
    if (e.file() != "<cam>") throw;
    bool from_set = false;
    for (const auto& s : overrides)
      if (s.rfind("cam.", 0) == 0) from_set = true;
    throw SceneError(from_set ? std::string("--set") : sc.source, 0, e.key(), e.value(),
                     e.rule());
  }
  resolve_defaults(sc);
  validate(sc);
  return sc;
}

/// The Simulator of a scene; model-building failures become SceneError as in the CLI.
std::unique_ptr<Simulator> make_simulator(const Scene& sc) {
  try {
    return std::make_unique<Simulator>(sc);
  } catch (const SceneError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(sc.source, 0, "scene", sc.title,
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
/// The observer's dict has the history_columns(), then (network scenes) the `extra`
/// columns (Simulator::extra_columns()).
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

// ---- bring your own follower: a Python follower as a camdyn::FollowerSystem ------------

std::string fmt_g(double x) {
  char b[64];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

/// A Python follower (the spec dict of camdyn._follower_spec()) as a FollowerSystem.
/// Constructed with the GIL held; every callback takes the GIL (py::gil_scoped_acquire), so
/// it works while the run has released it. The mass matrix is constant: factored here
/// (Cholesky), so solve_mass() never calls Python; kinetic energy defaults to ½ vᵀ M v.
class PyFollower final : public FollowerSystem {
 public:
  explicit PyFollower(const py::dict& spec) {
    auto bad = [](const std::string& key, const std::string& value, const std::string& rule) {
      throw SceneError("<follower>", 0, key, value, rule);
    };
    n_ = spec["size"].cast<int>();
    if (n_ < 1) bad("size", std::to_string(n_), "must be >= 1");
    const std::size_t n = std::size_t(n_);
    for (const py::handle c : spec["contacts"].cast<py::list>()) {
      const py::dict d = py::reinterpret_borrow<py::dict>(c);
      FollowerContact fc;
      fc.name = d["name"].cast<std::string>();
      fc.row = d["row"].cast<std::vector<double>>();
      fc.clearance = d["clearance"].cast<double>();
      fc.cam = d["cam"].cast<bool>();
      auto opt = [&](const char* k, std::optional<double>& x) {
        if (d.contains(k) && !d[k].is_none()) x = d[k].cast<double>();
      };
      opt("restitution", fc.restitution);
      opt("penalty_stiffness", fc.penalty_stiffness);
      opt("penalty_damping", fc.penalty_damping);
      contacts_.push_back(std::move(fc));
    }
    // M: n × n, symmetric positive definite; L Lᵀ = M (row-major L, lower).
    const auto M = spec["mass"].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
    if (M.ndim() != 2 || M.shape(0) != n_ || M.shape(1) != n_)
      bad("mass", "shape " + std::to_string(M.ndim() == 2 ? M.shape(0) : M.size()) + "...",
          "must be a size() x size() matrix");
    M_.assign(M.data(), M.data() + n * n);
    double scale = 0.0;
    for (double x : M_) {
      if (!std::isfinite(x)) bad("mass", "non-finite entry", "must be finite");
      scale = std::max(scale, std::abs(x));
    }
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (std::abs(M_[i * n + j] - M_[j * n + i]) > 1e-12 * scale)
          bad("mass", "[" + std::to_string(i) + "][" + std::to_string(j) + "] != [" + std::to_string(j) + "][" +
                          std::to_string(i) + "]",
              "must be symmetric");
    L_.assign(n * n, 0.0);
    for (std::size_t j = 0; j < n; ++j) {
      double d = M_[j * n + j];
      for (std::size_t k = 0; k < j; ++k) d -= L_[j * n + k] * L_[j * n + k];
      if (!(d > 0.0)) bad("mass", "pivot " + std::to_string(j), "must be positive definite");
      L_[j * n + j] = std::sqrt(d);
      for (std::size_t i = j + 1; i < n; ++i) {
        double s = M_[i * n + j];
        for (std::size_t k = 0; k < j; ++k) s -= L_[i * n + k] * L_[j * n + k];
        L_[i * n + j] = s / L_[j * n + j];
      }
    }
    force_ = spec["force"];
    jacobian_ = spec["jacobian"];
    kinetic_ = spec["kinetic_energy"];
    potential_ = spec["potential_energy"];
    damping_ = spec["damping_power"];
    linear_ = spec["linear"].cast<bool>();
    name_ = spec["name"].cast<std::string>();
    q0_.assign(n, 0.0);
    v0_.assign(n, 0.0);
    if (!spec["initial_state"].is_none()) {
      const auto qv = spec["initial_state"].cast<py::tuple>();
      q0_ = qv[0].cast<std::vector<double>>();
      v0_ = qv[1].cast<std::vector<double>>();
      if (q0_.size() != n || v0_.size() != n)
        bad("initial_state()", std::to_string(q0_.size()) + ", " + std::to_string(v0_.size()) + " entries",
            "must return (q0, v0) of size() entries each");
    }
  }
  ~PyFollower() override {
    py::gil_scoped_acquire gil;  // py::object members are released under the GIL
    force_ = jacobian_ = kinetic_ = potential_ = damping_ = py::object();
    pending_.reset();
  }

  int size() const override { return n_; }
  std::vector<FollowerContact> contacts() const override { return contacts_; }
  void force(double t, const double* q, const double* v, double* r) const override {
    call("force(t, q, v)", [&] {
      const auto a = as_array(force_(t, vec(q), vec(v)));
      expect(a, 1);
      std::copy(a.data(), a.data() + n_, r);
    });
  }
  void solve_mass(const double* b, double* x) const override {
    const std::size_t n = std::size_t(n_);
    for (std::size_t i = 0; i < n; ++i) {  // L y = b
      double s = b[i];
      for (std::size_t k = 0; k < i; ++k) s -= L_[i * n + k] * x[k];
      x[i] = s / L_[i * n + i];
    }
    for (std::size_t i = n; i-- > 0;) {  // Lᵀ x = y
      double s = x[i];
      for (std::size_t k = i + 1; k < n; ++k) s -= L_[k * n + i] * x[k];
      x[i] = s / L_[i * n + i];
    }
  }
  bool force_jacobian(double t, const double* q, const double* v, double* drdq, double* drdv) const override {
    if (jacobian_.is_none()) return false;
    call("jacobian(t, q, v)", [&] {
      const py::object res = jacobian_(t, vec(q), vec(v));
      const py::tuple pair(res);  // any sequence
      if (pair.size() != 2) throw BadReturn("returned " + std::to_string(pair.size()) + " items; expected a pair (dr_dq, dr_dv)");
      const std::size_t n = std::size_t(n_);
      for (int k = 0; k < 2; ++k) {
        double* out = k == 0 ? drdq : drdv;
        if (pair[k].is_none()) {  // dr_dv None: r does not depend on v
          std::fill(out, out + n * n, 0.0);
          continue;
        }
        const auto a = as_array(pair[k]);
        expect(a, 2);
        for (std::size_t i = 0; i < n; ++i)
          for (std::size_t j = 0; j < n; ++j) out[i + j * n] = a.data()[i * n + j];  // → column-major
      }
    });
    return true;
  }
  bool linear() const override { return linear_; }
  void initial_state(double* q, double* v) const override {
    std::copy(q0_.begin(), q0_.end(), q);
    std::copy(v0_.begin(), v0_.end(), v);
  }
  double kinetic_energy(const double* v) const override {
    if (kinetic_.is_none()) {  // ½ vᵀ M v
      const std::size_t n = std::size_t(n_);
      double e = 0.0;
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) e += v[i] * M_[i * n + j] * v[j];
      return 0.5 * e;
    }
    return scalar(kinetic_, "kinetic_energy(v)", v);
  }
  double potential_energy(const double* q) const override {
    return potential_.is_none() ? NAN : scalar(potential_, "potential_energy(q)", q);
  }
  double damping_power(const double* v) const override {
    return damping_.is_none() ? 0.0 : scalar(damping_, "damping_power(v)", v);
  }
  std::string name() const override { return name_; }

  /// Set while a run goes on: a failing callback also sets it, so the run ends at the next
  /// poll.
  void set_stop(std::atomic<bool>* stop) { stop_ = stop; }
  bool failed() const { return !error_.empty(); }
  bool has_pending() const { return pending_ != nullptr; }
  const std::string& error() const { return error_; }
  /// True if the kept Python exception is not an Exception (KeyboardInterrupt, SystemExit):
  /// to be re-raised rather than reported. Call with the GIL held.
  bool must_reraise() const {
    return pending_ && !PyErr_GivenExceptionMatches(pending_->type().ptr(), PyExc_Exception);
  }
  /// Re-raise the kept Python exception (GIL held).
  [[noreturn]] void rethrow() {
    std::unique_ptr<py::error_already_set> p = std::move(pending_);
    throw py::error_already_set(std::move(*p));
  }

 private:
  py::array_t<double> vec(const double* x) const { return py::array_t<double>(n_, x); }
  static py::array_t<double, py::array::c_style | py::array::forcecast> as_array(const py::handle& h) {
    return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
  }
  struct BadReturn : std::runtime_error {
    using std::runtime_error::runtime_error;
  };
  void expect(const py::array& a, int dims) const {
    const bool ok = a && (dims == 1 ? (a.size() == n_ && a.ndim() <= 1)
                                    : (a.ndim() == 2 && a.shape(0) == n_ && a.shape(1) == n_));
    if (!ok) {
      std::string got = !a ? std::string("not an array of numbers") : "shape (";
      if (a) {
        for (py::ssize_t i = 0; i < a.ndim(); ++i) got += (i ? ", " : "") + std::to_string(a.shape(i));
        got += a.ndim() == 1 ? ",)" : ")";
      }
      throw BadReturn("returned " + got + "; expected " +
                               (dims == 1 ? "size() = " + std::to_string(n_) + " values"
                                          : "a size() x size() = " + std::to_string(n_) + " x " +
                                                std::to_string(n_) + " matrix"));
    }
  }
  double scalar(const py::object& fn, const char* what, const double* x) const {
    double e = NAN;
    call(what, [&] { e = fn(vec(x)).cast<double>(); });
    return e;
  }
  /// Run `body` (which calls Python) under the GIL. A Python exception, or a bad return
  /// value, is kept (first one only) and ends the run: this and every later callback throw
  /// std::runtime_error with the text, which the engines turn into a failed step.
  template <class Body>
  void call(const char* what, Body&& body) const {
    if (failed()) throw std::runtime_error(error_);
    py::gil_scoped_acquire gil;
    try {
      body();
      return;
    } catch (py::error_already_set& e) {
      std::string text;
      try {
        text = py::str(e.type().attr("__name__")).cast<std::string>();
        const std::string msg = py::str(e.value()).cast<std::string>();
        if (!msg.empty()) text += ": " + msg;
      } catch (...) {
        text = e.what();
      }
      error_ = std::string("Python follower: ") + what + " raised " + text;
      pending_ = std::make_unique<py::error_already_set>(std::move(e));
    } catch (const BadReturn& e) {  // a return value of the wrong shape
      error_ = std::string("Python follower: ") + what + " " + e.what();
    } catch (const std::exception& e) {  // one that does not convert (py::cast_error)
      error_ = std::string("Python follower: ") + what + " returned a value that is not a number (" + e.what() + ")";
    }
    if (stop_) stop_->store(true);
    throw std::runtime_error(error_);
  }

  int n_ = 0;
  std::vector<FollowerContact> contacts_;
  std::vector<double> M_, L_, q0_, v0_;
  py::object force_, jacobian_, kinetic_, potential_, damping_;
  bool linear_ = false;
  std::string name_;
  std::atomic<bool>* stop_ = nullptr;
  mutable std::string error_;
  mutable std::unique_ptr<py::error_already_set> pending_;
};

/// A follower written in C++ (the test's cubic hardening valve spring,
/// tests/mechanism/test_follower_system.cpp): the native reference the Python follower's speed is
/// measured against (tests/python/test_follower.py).
struct CubicSpringFollower final : FollowerSystem {
  double m, k, k3, P;
  CubicSpringFollower(double m_, double k_, double k3_, double P_) : m(m_), k(k_), k3(k3_), P(P_) {}
  int size() const override { return 1; }
  std::vector<FollowerContact> contacts() const override {
    FollowerContact c;
    c.name = "cam";
    c.row = {1.0};
    return {c};
  }
  double spring(double q) const { return P + k * q + k3 * q * q * q; }
  void force(double, const double* q, const double*, double* r) const override { r[0] = -spring(q[0]); }
  void solve_mass(const double* b, double* x) const override { x[0] = b[0] / m; }
  bool force_jacobian(double, const double* q, const double*, double* drdq, double* drdv) const override {
    drdq[0] = -(k + 3 * k3 * q[0] * q[0]);
    drdv[0] = 0.0;
    return true;
  }
  double kinetic_energy(const double* v) const override { return 0.5 * m * v[0] * v[0]; }
  double potential_energy(const double* q) const override {
    return P * q[0] + 0.5 * k * q[0] * q[0] + 0.25 * k3 * std::pow(q[0], 4);
  }
  std::string name() const override { return "cubic valve spring (C++)"; }
};

/// run(): (summary JSON text, {column: float64 array}, [event dicts]). Network scenes:
/// the history has the extra columns (F_<contact>, gap_<contact>, in_<contact>, u_<node>,
/// v_<node>) after the standard ones, and each event dict has "contact".
/// With a user's follower (`follower`: a FollowerSystem made in C++, or the spec dict of a
/// Python follower, camdyn._follower_spec()), the scene's follower is replaced by it.
py::tuple run_scene(const std::string& kind, const std::string& text, const std::string& source,
                    const std::vector<std::string>& overrides, py::object observer,
                    const py::object& follower) {
  const Scene sc = build_scene(kind, text, source, overrides);
  std::unique_ptr<Simulator> sim;
  std::shared_ptr<PyFollower> pyf;
  if (follower.is_none()) {
    sim = make_simulator(sc);
  } else {
    std::shared_ptr<const FollowerSystem> fs;
    if (py::isinstance<FollowerSystem>(follower)) {
      fs = follower.cast<std::shared_ptr<FollowerSystem>>();
    } else {
      pyf = std::make_shared<PyFollower>(follower.cast<py::dict>());
      fs = pyf;
    }
    try {
      sim = std::make_unique<Simulator>(sc, fs);  // checks the follower (SceneError "<follower>")
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
  if (pyf) pyf->set_stop(nullptr);
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

  // network columns: any extra besides the designer columns (run.designer_columns, last)
  const bool network_cols = extra.size() > (sim->scene().run.designer_columns ? 6u : 0u);
  py::list events;
  for (const auto& e : summary.events) {
    py::dict d;
    d["t"] = e.t;
    d["kind"] = e.kind;
    d["impact_velocity"] = e.impact_velocity;
    d["theta"] = e.theta;
    d["impulse"] = e.impulse;
    if (network_cols) d["contact"] = e.contact;  // network scenes (as events.csv)
    events.append(d);
  }
  return py::make_tuple(summary_json(summary, sc), history, events);
}

py::dict jump(const std::string& kind, const std::string& text, const std::string& source,
              const std::vector<std::string>& overrides, const py::dict& options, const py::object& follower) {
  const Scene sc = build_scene(kind, text, source, overrides);
  // A user follower (issue 28): a C++ FollowerSystem, or a Python one's spec dict.
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
  std::vector<Scene> scenes;
  scenes.reserve(specs.size());
  for (const auto& [kind, text, source, overrides] : specs)
    scenes.push_back(build_scene(kind, text, source, overrides));
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
    if (sums[i].scene.empty()) sums[i].scene = scenes[i].title;
    out.push_back(summary_json(sums[i], scenes[i]));
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
  m.def("resolved_scene",
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
  m.def("cam_motion", &cam_motion, py::arg("kind"), py::arg("text"), py::arg("source"),
        py::arg("overrides"), py::arg("t"), py::arg("lift") = false);
  m.def("initial_state_on_cam", &on_cam, py::arg("kind"), py::arg("text"), py::arg("source"),
        py::arg("overrides"), py::arg("follower"));
}
