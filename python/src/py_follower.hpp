// camdyn._camdyn — followers for Python's run_follower (camdyn_module.cpp): a Python
// follower (the spec dict of camdyn._follower_spec()) as a camdyn::FollowerSystem, and a
// C++ follower exposed to Python as the native reference of its speed.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camdyn/follower_system.hpp"
#include "camdyn/scene.hpp"

namespace camdyn_python {

namespace py = pybind11;
using namespace camdyn;

/// "%.6g" (a time in a run message).
inline std::string fmt_g(double x) {
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

}  // namespace camdyn_python
