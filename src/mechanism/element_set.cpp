// camdyn — the nonlinear elements of a mechanism (element_set.hpp).
#include "mechanism/element_set.hpp"

#include <stdexcept>

namespace camdyn {

namespace {
// per-thread scratch for an element's x, ẋ, f and Jacobian blocks
struct Scratch {
  std::vector<double> x, xd, f, dfdx, dfdxd;
};
Scratch& scratch(int nodes) {
  thread_local Scratch s;
  const std::size_t k = std::size_t(nodes);
  if (s.x.size() < k) {
    s.x.resize(k);
    s.xd.resize(k);
    s.f.resize(k);
    s.dfdx.resize(k * k);
    s.dfdxd.resize(k * k);
  }
  return s;
}
}  // namespace

void ElementSet::add(std::unique_ptr<const Element> element, std::vector<Row> rows) {
  if (element->states() > 0)
    throw std::invalid_argument("element '" + element->name() +
                                "': elements with internal states are not integrated by the engines yet");
  Placed p;
  p.element = std::move(element);
  p.rows = std::move(rows);
  placed_.push_back(std::move(p));
}

void ElementSet::finish(int n) {
  n_ = n;
  using Trip = Eigen::Triplet<double, long>;
  std::vector<Trip> tk, tc;
  bool any_c = false;
  for (const Placed& p : placed_) {
    const int k = p.element->nodes();
    any_c |= p.element->damps();
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i)
        for (const auto& b : p.rows[std::size_t(j)])
          for (const auto& a : p.rows[std::size_t(i)]) {
            tk.emplace_back(a.first, b.first, 0.0);
            if (p.element->damps()) tc.emplace_back(a.first, b.first, 0.0);
          }
  }
  Ke_.resize(n, n);
  Ke_.setFromTriplets(tk.begin(), tk.end());
  Ke_.makeCompressed();
  if (any_c) {
    Ce_.resize(n, n);
    Ce_.setFromTriplets(tc.begin(), tc.end());
    Ce_.makeCompressed();
  } else {
    Ce_.resize(0, 0);
  }
  auto position = [](const SparseMatrix& S, long i, long j) {
    for (long p = S.outerIndexPtr()[j]; p < S.outerIndexPtr()[j + 1]; ++p)
      if (S.innerIndexPtr()[p] == i) return p;
    throw std::logic_error("ElementSet: entry outside the pattern");
  };
  for (Placed& p : placed_) {
    const int k = p.element->nodes();
    p.pos_k.clear();
    p.pos_c.clear();
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i)
        for (const auto& b : p.rows[std::size_t(j)])
          for (const auto& a : p.rows[std::size_t(i)]) {
            p.pos_k.push_back(position(Ke_, a.first, b.first));
            if (p.element->damps()) p.pos_c.push_back(position(Ce_, a.first, b.first));
          }
  }
}

ElementState ElementSet::gather(const Placed& p, double t, const double* q, const double* v) const {
  const int k = p.element->nodes();
  Scratch& s = scratch(k);
  for (int i = 0; i < k; ++i) {
    double x = 0.0, xd = 0.0;
    for (const auto& e : p.rows[std::size_t(i)]) {
      x += e.second * q[e.first];
      if (v) xd += e.second * v[e.first];
    }
    s.x[std::size_t(i)] = x;
    s.xd[std::size_t(i)] = xd;
  }
  ElementState e;
  e.t = t;
  e.x = s.x.data();
  e.xd = s.xd.data();
  return e;
}

void ElementSet::add_force(double t, const double* q, const double* v, double* r) const {
  for (const Placed& p : placed_) {
    const ElementState e = gather(p, t, q, v);
    const int k = p.element->nodes();
    double* f = scratch(k).f.data();
    p.element->force(e, f);
    for (int i = 0; i < k; ++i)
      for (const auto& e : p.rows[std::size_t(i)]) r[e.first] += e.second * f[i];
  }
}

void ElementSet::tangent(double t, const double* q, const double* v, SparseMatrix& Ke, SparseMatrix& Ce) const {
  if (Ke.nonZeros() != Ke_.nonZeros()) Ke = Ke_;
  if (damps() && Ce.nonZeros() != Ce_.nonZeros()) Ce = Ce_;
  double* kv = Ke.valuePtr();
  std::fill(kv, kv + Ke.nonZeros(), 0.0);
  double* cv = damps() ? Ce.valuePtr() : nullptr;
  if (cv) std::fill(cv, cv + Ce.nonZeros(), 0.0);
  for (const Placed& p : placed_) {
    const ElementState e = gather(p, t, q, v);
    const int k = p.element->nodes();
    Scratch& s = scratch(k);
    const bool c = p.element->damps();
    p.element->force_jacobian(e, s.dfdx.data(), c ? s.dfdxd.data() : nullptr);
    std::size_t n = 0;
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const std::size_t ij = std::size_t(i + j * k);
        for (const auto& b : p.rows[std::size_t(j)])
          for (const auto& a : p.rows[std::size_t(i)]) {
            const double ww = a.second * b.second;
            kv[p.pos_k[n]] -= ww * s.dfdx[ij];
            if (c) cv[p.pos_c[n]] -= ww * s.dfdxd[ij];
            ++n;
          }
      }
  }
}

double ElementSet::stored_energy(const double* q) const {
  double V = 0.0;
  for (const Placed& p : placed_) V += p.element->stored_energy(gather(p, 0.0, q, nullptr));
  return V;
}

double ElementSet::dissipated_power(double t, const double* q, const double* v) const {
  double P = 0.0;
  for (const Placed& p : placed_)
    P += p.element->dissipated_power(gather(p, t, q, v));  // also without ẋ: an external force's work
  return P;
}

std::vector<std::string> ElementSet::force_names() const {
  std::vector<std::string> n;
  for (const Placed& p : placed_)
    for (const std::string& s : p.element->force_names()) n.push_back(s);
  return n;
}

void ElementSet::forces(double t, const double* q, const double* v, double* out) const {
  for (const Placed& p : placed_) {
    p.element->forces(gather(p, t, q, v), out);
    out += p.element->force_names().size();
  }
}

}  // namespace camdyn
