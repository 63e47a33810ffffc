// camdyn — the nonlinear elements of a mechanism (element_set.hpp).
#include "mechanism/element_set.hpp"

#include <algorithm>
#include <stdexcept>

namespace camdyn {

namespace {
// per-thread scratch for an element's x, ẋ, f and Jacobian blocks
struct Scratch {
  std::vector<double> x, xd, f, dfdx, dfdxd, dgdx, dgdxd, dgds, dfds;
};
Scratch& scratch(int nodes, int states = 0) {
  thread_local Scratch s;
  const std::size_t k = std::size_t(nodes), m = std::size_t(states);
  if (s.x.size() < k) {
    s.x.resize(k);
    s.xd.resize(k);
    s.f.resize(k);
    s.dfdx.resize(k * k);
    s.dfdxd.resize(k * k);
  }
  if (s.dgds.size() < m * m || s.dgdx.size() < m * k) {
    s.dgdx.resize(std::max(s.dgdx.size(), m * k));
    s.dgdxd.resize(std::max(s.dgdxd.size(), m * k));
    s.dfds.resize(std::max(s.dfds.size(), m * k));
    s.dgds.resize(std::max(s.dgds.size(), m * m));
  }
  return s;
}
}  // namespace

void ElementSet::add(std::unique_ptr<const Element> element, std::vector<Row> rows) {
  Placed p;
  p.state_offset = ns_;
  ns_ += element->states();
  p.element = std::move(element);
  p.rows = std::move(rows);
  bool direct = true;
  for (const Row& r : p.rows) direct = direct && r.size() <= 1;
  if (direct)
    for (const Row& r : p.rows) {
      p.unknown.push_back(r.empty() ? -1 : r[0].first);
      p.coefficient.push_back(r.empty() ? 0.0 : r[0].second);
    }
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
  // the state blocks' patterns: R_s (n × ns) and G_q = G_v (ns × n) on the element's unknowns
  std::vector<Trip> tr, tg;
  for (const Placed& p : placed_)
    for (int l = 0; l < p.element->states(); ++l)
      for (const Row& row : p.rows)
        for (const auto& a : row) {
          tr.emplace_back(a.first, p.state_offset + l, 0.0);
          tg.emplace_back(p.state_offset + l, a.first, 0.0);
        }
  Rs_.resize(n, ns_);
  Rs_.setFromTriplets(tr.begin(), tr.end());
  Rs_.makeCompressed();
  Gq_.resize(ns_, n);
  Gq_.setFromTriplets(tg.begin(), tg.end());
  Gq_.makeCompressed();
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

namespace {
// Element p's state from its nodes' x, ẋ (already gathered) and its internal states in st.
ElementState element_state(const ElementSet::Placed& p, double t, const double* st, double* x, double* xd) {
  ElementState e;
  e.t = t;
  e.x = x;
  e.xd = xd;
  if (p.element->states() > 0) {
    if (!st) throw std::logic_error("ElementSet: element '" + p.element->name() + "' needs its internal states");
    e.s = st + p.state_offset;
  }
  return e;
}

// Element p's state at (t, q, v, s): its nodes' x and ẋ into x, xd (nodes() entries each).
ElementState state_into(const ElementSet::Placed& p, double t, const double* q, const double* v, const double* st,
                        double* x, double* xd) {
  const int k = p.element->nodes();
  for (int i = 0; i < k; ++i) {
    double xi = 0.0, xdi = 0.0;
    for (const auto& e : p.rows[std::size_t(i)]) {
      xi += e.second * q[e.first];
      if (v) xdi += e.second * v[e.first];
    }
    x[i] = xi;
    xd[i] = xdi;
  }
  return element_state(p, t, st, x, xd);
}
// Elements of up to this many nodes keep x, ẋ and f on the stack in the calls made at every
// right-hand side (add_force, dissipated_power); larger ones use the per-thread scratch.
constexpr int kStackNodes = 8;
// state_into for an element whose nodes are each on at most one unknown (Placed::unknown).
inline ElementState direct_state(const ElementSet::Placed& p, double t, const double* q, const double* v,
                                 const double* st, double* x, double* xd) {
  const int k = p.element->nodes();
  const int* u = p.unknown.data();
  const double* c = p.coefficient.data();
  for (int i = 0; i < k; ++i) {
    const bool on = u[i] >= 0;
    x[i] = on ? c[i] * q[u[i]] : 0.0;
    xd[i] = on && v ? c[i] * v[u[i]] : 0.0;
  }
  return element_state(p, t, st, x, xd);
}
}  // namespace

ElementState ElementSet::gather(const Placed& p, double t, const double* q, const double* v,
                                const double* st) const {
  Scratch& s = scratch(p.element->nodes());
  return state_into(p, t, q, v, st, s.x.data(), s.xd.data());
}

void ElementSet::add_force(double t, const double* q, const double* v, double* r, const double* st) const {
  double x[kStackNodes], xd[kStackNodes], fl[kStackNodes];
  for (const Placed& p : placed_) {
    const int k = p.element->nodes();
    if (!p.unknown.empty() && k <= kStackNodes) {
      p.element->force(direct_state(p, t, q, v, st, x, xd), fl);
      for (int i = 0; i < k; ++i)
        if (p.unknown[std::size_t(i)] >= 0) r[p.unknown[std::size_t(i)]] += p.coefficient[std::size_t(i)] * fl[i];
      continue;
    }
    double* f = fl;
    ElementState e;
    if (k <= kStackNodes) {
      e = state_into(p, t, q, v, st, x, xd);
    } else {
      e = gather(p, t, q, v, st);
      f = scratch(k).f.data();
    }
    p.element->force(e, f);
    for (int i = 0; i < k; ++i)
      for (const auto& en : p.rows[std::size_t(i)]) r[en.first] += en.second * f[i];
  }
}

void ElementSet::tangent(double t, const double* q, const double* v, SparseMatrix& Ke, SparseMatrix& Ce,
                         const double* st) const {
  if (Ke.nonZeros() != Ke_.nonZeros()) Ke = Ke_;
  if (damps() && Ce.nonZeros() != Ce_.nonZeros()) Ce = Ce_;
  double* kv = Ke.valuePtr();
  std::fill(kv, kv + Ke.nonZeros(), 0.0);
  double* cv = damps() ? Ce.valuePtr() : nullptr;
  if (cv) std::fill(cv, cv + Ce.nonZeros(), 0.0);
  for (const Placed& p : placed_) {
    const ElementState e = gather(p, t, q, v, st);
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

void ElementSet::initial_states(double* s0) const {
  for (const Placed& p : placed_)
    if (p.element->states() > 0) p.element->initial_states(s0 + p.state_offset);
}

void ElementSet::state_rate(double t, const double* q, const double* v, const double* st, double* sdot) const {
  for (const Placed& p : placed_)
    if (p.element->states() > 0) p.element->state_rate(gather(p, t, q, v, st), sdot + p.state_offset);
}

void ElementSet::state_tangent(double t, const double* q, const double* v, const double* st, SparseMatrix& Rs,
                               SparseMatrix& Gq, SparseMatrix& Gv, Eigen::MatrixXd& Gs) const {
  if (Rs.nonZeros() != Rs_.nonZeros()) Rs = Rs_;
  if (Gq.nonZeros() != Gq_.nonZeros()) Gq = Gq_;
  if (Gv.nonZeros() != Gq_.nonZeros()) Gv = Gq_;
  std::fill(Rs.valuePtr(), Rs.valuePtr() + Rs.nonZeros(), 0.0);
  std::fill(Gq.valuePtr(), Gq.valuePtr() + Gq.nonZeros(), 0.0);
  std::fill(Gv.valuePtr(), Gv.valuePtr() + Gv.nonZeros(), 0.0);
  Gs.setZero(ns_, ns_);
  for (const Placed& p : placed_) {
    const int k = p.element->nodes(), ms = p.element->states();
    if (ms == 0) continue;
    const ElementState e = gather(p, t, q, v, st);
    Scratch& s = scratch(k, ms);
    std::fill(s.dgdx.begin(), s.dgdx.end(), 0.0);
    std::fill(s.dgdxd.begin(), s.dgdxd.end(), 0.0);
    std::fill(s.dgds.begin(), s.dgds.end(), 0.0);
    std::fill(s.dfds.begin(), s.dfds.end(), 0.0);
    p.element->state_jacobian(e, s.dgdx.data(), s.dgdxd.data(), s.dgds.data(), s.dfds.data());
    const int o = p.state_offset;
    for (int l = 0; l < ms; ++l) {
      for (int c = 0; c < ms; ++c) Gs(o + l, o + c) = s.dgds[std::size_t(l + c * ms)];
      for (int i = 0; i < k; ++i)
        for (const auto& a : p.rows[std::size_t(i)]) {
          Rs.coeffRef(a.first, o + l) += a.second * s.dfds[std::size_t(i + l * k)];
          Gq.coeffRef(o + l, a.first) += s.dgdx[std::size_t(l + i * ms)] * a.second;
          Gv.coeffRef(o + l, a.first) += s.dgdxd[std::size_t(l + i * ms)] * a.second;
        }
    }
  }
}

double ElementSet::stored_energy(const double* q, const double* st) const {
  double V = 0.0;
  for (const Placed& p : placed_)
    V += p.element->stored_energy(gather(p, 0.0, q, nullptr, st));
  return V;
}

double ElementSet::dissipated_power(double t, const double* q, const double* v, const double* st) const {
  double P = 0.0;
  double x[kStackNodes], xd[kStackNodes];
  for (const Placed& p : placed_) {  // also without ẋ: an external force's work
    const bool stack = p.element->nodes() <= kStackNodes;
    P += p.element->dissipated_power(stack && !p.unknown.empty() ? direct_state(p, t, q, v, st, x, xd)
                                     : stack                     ? state_into(p, t, q, v, st, x, xd)
                                                                 : gather(p, t, q, v, st));
  }
  return P;
}

std::vector<std::string> ElementSet::force_names() const {
  std::vector<std::string> n;
  for (const Placed& p : placed_)
    for (const std::string& s : p.element->force_names()) n.push_back(s);
  return n;
}

void ElementSet::forces(double t, const double* q, const double* v, double* out, const double* st) const {
  for (const Placed& p : placed_) {
    p.element->forces(gather(p, t, q, v, st), out);
    out += p.element->force_names().size();
  }
}

}  // namespace camdyn
