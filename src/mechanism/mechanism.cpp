// camdyn — the Mechanism of every scene: the network builder (here; a rigid or elastic-bar follower: follower_builder.cpp) and the run-time maths (src/mechanism/mechanism.hpp).
#include "mechanism/mechanism.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "cam/format.hpp"            // detail::fmt
#include "scene/linear_solver.hpp"  // resolve_linear_solver
#include "mechanism/element.hpp"

namespace camdyn {

namespace {
std::string element_label(const ElementSpec& e, size_t i) {
  return e.name.empty() ? std::string(to_string(e.kind)) + " #" + std::to_string(i) : e.name;
}
}  // namespace

std::string element_report_name(const ElementSpec& e, std::size_t index) {
  return e.name.empty() ? std::string(to_string(e.kind)) + "_" + std::to_string(index) : e.name;
}


Mechanism::Mechanism(const Scene& scene) {
  using detail::fmt;
  if (scene.follower.kind != FollowerKind::Network) {
    build_follower(scene);
    return;
  }
  // A [camshaft]: its stations are nodes "shaft_<i>" whose coordinate is the shaft angle,
  // its segments and Rayleigh damping springs and dashpots (camshaft.hpp).
  NetworkSpec shaft_net;
  const bool shaft = scene.camshaft.present();
  if (shaft) shaft_net = network_with_camshaft(scene);
  const NetworkSpec& net = shaft ? shaft_net : scene.network;
  std::map<std::string, int> index;  // named node → full DOF
  for (const NodeSpec& nd : net.nodes) {
    index[nd.name] = int(node_names_.size());
    node_names_.push_back(nd.name);
  }
  const int n_named = int(node_names_.size());
  auto dof = [&](const std::string& name) { return name == "ground" ? -1 : index.at(name); };

  // ---- full DOFs: named nodes, then the inside nodes of bars and springs with mass
  int n_full = n_named;
  struct Stiff { int a, b; double k, c, P; };  // two-node spring/damper/preload, −1 = ground
  std::vector<Stiff> links;
  std::vector<std::pair<int, double>> point_mass;  // (dof, mass)
  struct MassPair { int a, b; double md, mo; };    // element mass matrix [md mo; mo md]
  std::vector<MassPair> mass_pairs;
  // a lever: out = ratio·in + (1 − ratio)·pivot (pivot −1: fixed, out = ratio·in)
  struct LeverTie { int out, in, pivot; double ratio; };
  std::vector<LeverTie> levers;
  std::vector<std::pair<int, int>> inner_ends;  // per inner node: its chain's end DOFs
  std::vector<double> inner_frac;               // position along the chain (0 at a, 1 at b)
  for (size_t i = 0; i < net.nodes.size(); ++i)
    if (net.nodes[i].mass > 0.0) point_mass.emplace_back(int(i), net.nodes[i].mass);
  bool any_damping = false, any_preload = false, any_mass_matrix = false;
  struct Nonlinear { std::unique_ptr<Element> element; std::vector<int> nodes; };
  std::vector<Nonlinear> nonlinear;
  struct TwoNodeForce { std::string name; int a, b; double k, c, P; };  // a reported linear force
  std::vector<TwoNodeForce> two_node;
  // a coil-to-coil contact of a spring whose coils clash: segment lower → upper closes at gap
  struct CoilContact { std::string spring, name; int lower, upper; double gap; std::optional<double> e; };
  std::vector<CoilContact> coils;
  std::vector<std::pair<std::string, std::vector<int>>> surge_chains;  // springs with coil masses
  for (size_t ei = 0; ei < net.elements.size(); ++ei) {
    const ElementSpec& e = net.elements[ei];
    const int a = dof(e.nodes.at(0)), b = dof(e.nodes.at(1));
    std::ostringstream d;
    d << to_string(e.kind) << " '" << element_label(e, ei) << "' [" << e.nodes[0] << " → "
      << e.nodes[1] << "]";
    // A chain of `parts` equal segments a → inner … → b; returns the DOFs along it.
    auto chain = [&](int parts) {
      std::vector<int> c{a};
      for (int k = 1; k < parts; ++k) {
        c.push_back(n_full++);
        inner_ends.emplace_back(a, b);
        inner_frac.push_back(double(k) / parts);
      }
      c.push_back(b);
      return c;
    };
    switch (e.kind) {
      case ElementKind::Spring:
      case ElementKind::Dashpot: {
        const double k = e.kind == ElementKind::Spring ? e.stiffness : 0.0;
        const double P = e.kind == ElementKind::Spring ? e.preload : 0.0;
        any_damping |= e.damping != 0.0;
        any_preload |= P != 0.0;
        std::vector<int> ends{a, b};  // the coil chain's DOFs (a spring without masses: its two ends)
        if (e.kind == ElementKind::Spring && e.masses > 0) {
          const int parts = e.masses + 1;
          const std::vector<int> c = chain(parts);
          ends = c;
          surge_chains.emplace_back(element_report_name(e, ei), c);
          const double ms = e.mass / parts;
          for (int s = 0; s < parts; ++s) {
            links.push_back({c[s], c[s + 1], k * parts, e.damping * parts, P});
            mass_pairs.push_back({c[s], c[s + 1], 0.5 * ms, 0.0});
          }
          d << " k " << fmt(k) << ", preload " << fmt(P) << ", mass " << fmt(e.mass) << " in "
            << e.masses << " masses";
        } else {
          links.push_back({a, b, k, e.damping, P});
          two_node.push_back({element_report_name(e, ei), a, b, k, e.damping, P});
          if (e.kind == ElementKind::Spring) d << " k " << fmt(k) << ", preload " << fmt(P);
        }
        if (e.damping != 0.0) d << ", c " << fmt(e.damping);
        if (e.kind == ElementKind::Spring && e.solid_length > 0) {
          const int parts = int(ends.size()) - 1;
          const double travel = e.free_length - e.preload / e.stiffness - e.solid_length;
          const std::string sn = element_report_name(e, ei);
          for (int s = 0; s < parts; ++s)
            coils.push_back({sn, sn + "_coil" + std::to_string(s), ends[s], ends[s + 1],
                             e.coil_gaps.empty() ? travel / parts : e.coil_gaps[s], e.coil_restitution});
          d << ", coils clash: " << parts << " gaps adding up to " << fmt(travel) << " (solid length "
            << fmt(e.solid_length) << ")";
        }
        break;
      }
      case ElementKind::Bar: {
        const int N = e.elements;
        const std::vector<int> c = chain(N);
        const double h = e.length / N, ke = e.youngs_modulus * e.area / h, me = e.mass / N;
        const bool lumped = e.mass_matrix == BarMass::Lumped;
        any_mass_matrix |= !lumped;
        any_damping |= e.rayleigh_alpha != 0.0 || e.rayleigh_beta != 0.0;
        for (int s = 0; s < N; ++s) {
          const double md = lumped ? me / 2 : me / 3, mo = lumped ? 0.0 : me / 6;
          // Rayleigh on the element: c = α·(mass part) + β·ke (the mass part's
          // off-diagonal enters C through mass_pairs below)
          links.push_back({c[s], c[s + 1], ke, e.rayleigh_beta * ke, 0.0});
          mass_pairs.push_back({c[s], c[s + 1], md, mo});
          if (e.rayleigh_alpha != 0.0) {
            // C += α Mₑ, written as a link with c = −α·mo (off-diagonal) plus diagonal terms
            links.push_back({c[s], c[s + 1], 0.0, -e.rayleigh_alpha * mo, 0.0});
            // diagonal α(md + mo) on both ends: a damper to ground at each end
            links.push_back({c[s], -1, 0.0, e.rayleigh_alpha * (md + mo), 0.0});
            links.push_back({c[s + 1], -1, 0.0, e.rayleigh_alpha * (md + mo), 0.0});
          }
        }
        d << " " << N << " elements, EA " << fmt(e.youngs_modulus * e.area) << ", L "
          << fmt(e.length) << ", mass " << fmt(e.mass) << (lumped ? " lumped" : " consistent");
        break;
      }
      case ElementKind::Lever:
        levers.push_back({b, a, e.nodes.size() == 3 ? dof(e.nodes[2]) : -1, e.ratio});
        d << " ratio " << fmt(e.ratio);
        if (e.nodes.size() == 3) d << ", pivot " << e.nodes[2] << " (moving)";
        break;
      case ElementKind::ProgressiveSpring:
      case ElementKind::GuideFriction:
      case ElementKind::GasLoad:
      case ElementKind::HydraulicLashAdjuster: {
        std::unique_ptr<Element> el = make_element(e, element_report_name(e, ei), &scene);
        any_damping |= el->damps();
        d.str(el->describe());
        nonlinear.push_back({std::move(el), {a, b}});
        break;
      }
    }
    desc_.network.push_back(d.str());
  }
  if (shaft && scene.camshaft.drive == CamshaftDrive::Compliant) {
    // the drive coupling: −k_d φ_d − c_d φ̇_d here, the crank's part in acceleration()
    const CamshaftSpec& c = scene.camshaft;
    links.push_back({index.at("shaft_" + std::to_string(c.drive_station)), -1, c.drive_stiffness,
                     c.drive_damping, 0.0});
    any_damping |= c.drive_damping != 0.0;
  }

  // ---- levers: q_full = Lf q (an output is ratio × its input plus (1 − ratio) × its
  //      pivot when the pivot moves; chains resolved: a row of Lf has one entry per
  //      independent node it depends on)
  using Row = std::vector<std::pair<int, double>>;  // (reduced DOF, coefficient)
  std::vector<int> red(n_full, -1);
  std::map<int, const LeverTie*> dep;
  for (const LeverTie& lv : levers) dep[lv.out] = &lv;
  n_ = 0;
  for (int i = 0; i < n_full; ++i)
    if (!dep.count(i)) red[i] = n_++;
  std::vector<Row> lrow(n_full);
  std::vector<char> state(n_full, 0);  // 0 unresolved, 1 in progress, 2 done
  std::function<const Row&(int)> resolve = [&](int i) -> const Row& {
    if (state[i] == 2) return lrow[i];
    if (state[i] == 1) throw std::invalid_argument("levers form a cycle");
    state[i] = 1;
    Row r;
    const auto it = dep.find(i);
    if (it == dep.end()) {
      r.emplace_back(red[i], 1.0);
    } else {
      const LeverTie& lv = *it->second;
      std::map<int, double> sum;
      for (const auto& e : resolve(lv.in)) sum[e.first] += lv.ratio * e.second;
      if (lv.pivot >= 0)
        for (const auto& e : resolve(lv.pivot)) sum[e.first] += (1.0 - lv.ratio) * e.second;
      for (const auto& e : sum)
        if (e.second != 0.0) r.push_back(e);
    }
    lrow[i] = std::move(r);
    state[i] = 2;
    return lrow[i];
  };
  for (int i = 0; i < n_full; ++i) resolve(i);

  // ---- assemble M, K, C, f₀ directly over the reduced DOFs: Lfᵀ A Lf entry by entry
  using Trip = Eigen::Triplet<double, long>;
  std::vector<Trip> tm, tk, tc;
  Eigen::VectorXd ff = Eigen::VectorXd::Zero(n_full);
  // x [1 −1; −1 1] on full DOFs (a, b); ground (−1) and grounded lever outputs dropped
  // (ground and grounded rows are empty): x (r_a − r_b)ᵀ(r_a − r_b) with r the rows of Lf
  const Row ground_row;
  auto row = [&](int i) -> const Row& { return i >= 0 ? lrow[i] : ground_row; };
  auto add2 = [&](std::vector<Trip>& A, int a, int b, double x) {
    if (x == 0.0) return;
    Row d = row(a);
    for (const auto& e : row(b)) d.emplace_back(e.first, -e.second);
    for (const auto& u : d)
      for (const auto& w : d) A.emplace_back(u.first, w.first, x * u.second * w.second);
  };
  for (const Stiff& l : links) {
    add2(tk, l.a, l.b, l.k);
    add2(tc, l.a, l.b, l.c);
    if (l.a >= 0) ff[l.a] -= l.P;
    if (l.b >= 0) ff[l.b] += l.P;
  }
  auto add_mass = [&](int a, int b, double x) {  // x on (a, b) of the full mass matrix
    for (const auto& u : row(a))
      for (const auto& w : row(b)) tm.emplace_back(u.first, w.first, x * u.second * w.second);
  };
  for (const auto& pm : point_mass) add_mass(pm.first, pm.first, pm.second);
  for (const MassPair& p : mass_pairs) {
    add_mass(p.a, p.a, p.md);
    add_mass(p.b, p.b, p.md);
    if (p.mo != 0.0) {
      add_mass(p.a, p.b, p.mo);
      add_mass(p.b, p.a, p.mo);
    }
  }
  M_.resize(n_, n_);
  K_.resize(n_, n_);
  M_.setFromTriplets(tm.begin(), tm.end());
  K_.setFromTriplets(tk.begin(), tk.end());
  if (any_damping) {
    C_.resize(n_, n_);
    C_.setFromTriplets(tc.begin(), tc.end());
  }
  f0_ = Eigen::VectorXd::Zero(n_);
  for (int i = 0; i < n_full; ++i)
    for (const auto& e : lrow[i]) f0_[e.first] += e.second * ff[i];
  {
    std::vector<Trip> tl;
    for (int i = 0; i < n_named; ++i)
      for (const auto& e : lrow[i]) tl.emplace_back(i, e.first, e.second);
    L_.resize(n_named, n_);
    L_.setFromTriplets(tl.begin(), tl.end());
  }

  factor_mass();

  // ---- nonlinear elements and the reported linear forces, on the reduced DOFs
  for (Nonlinear& nl : nonlinear) {
    std::vector<Row> rows;
    for (int i : nl.nodes) rows.push_back(row(i));
    elements_.add(std::move(nl.element), std::move(rows));
  }
  elements_.finish(n_);
  s0_ = Eigen::VectorXd::Zero(elements_.states());
  elements_.initial_states(s0_.data());
  for (const TwoNodeForce& f : two_node) linear_forces_.push_back({f.name, row(f.a), row(f.b), f.k, f.c, f.P});
  for (const auto& sc : surge_chains) {  // x_i − (1 − f_i) x_a − f_i x_b, f_i = i/parts
    SurgeChain s{sc.first, {}};
    const std::vector<int>& c = sc.second;
    const int parts = int(c.size()) - 1;
    for (int i = 1; i < parts; ++i) {
      const double f = double(i) / parts;
      std::vector<std::pair<int, double>> r = row(c[i]);
      for (const auto& e : row(c[0])) r.emplace_back(e.first, -(1.0 - f) * e.second);
      for (const auto& e : row(c[parts])) r.emplace_back(e.first, -f * e.second);
      s.rows.push_back(std::move(r));
    }
    surge_.push_back(std::move(s));
  }

  // ---- contacts
  for (const ContactPointSpec& cs : net.contacts) {
    MechanismContact c;
    c.name = cs.name;
    c.kind = cs.kind;
    Eigen::RowVectorXd tr = Eigen::RowVectorXd::Zero(n_);  // the row over the reduced DOFs
    auto tf = [&](int i, double x) {
      for (const auto& e : row(i)) tr[e.first] += x * e.second;
    };
    const int a = dof(cs.nodes.at(0));
    std::ostringstream d;
    d << "contact '" << cs.name << "' (" << to_string(cs.kind) << ", ";
    switch (cs.kind) {
      case ContactPointKind::Cam:
        tf(a, 1.0);
        c.cam = true;
        d << "cam on " << cs.nodes[0];
        break;
      case ContactPointKind::Lash:
        tf(dof(cs.nodes.at(1)), 1.0);
        tf(a, -1.0);
        d << cs.nodes[0] << " below " << cs.nodes[1];
        break;
      case ContactPointKind::Stop:
        tf(a, cs.side == StopSide::Below ? 1.0 : -1.0);
        d << "stop " << to_string(cs.side) << " " << cs.nodes[0];
        break;
    }
    c.g0 = cs.clearance;
    c.t = tr;
    c.law = ContactLaw::of(scene.contact, cs.restitution, cs.penalty_stiffness, cs.penalty_damping);
    d << ", clearance " << fmt(c.g0) << ", e " << fmt(c.law.impact.restitution) << ")";
    desc_.network.push_back(d.str());
    contacts_.push_back(std::move(c));
  }
  // ---- coil-to-coil contacts of springs whose coils clash: a lash contact per segment,
  //      g = q_upper − q_lower + gap (the segment's compression reaches its gap: coil clash)
  for (const CoilContact& cc : coils) {
    MechanismContact c;
    c.name = cc.name;
    c.kind = ContactPointKind::Lash;
    c.coil_spring = cc.spring;
    Eigen::RowVectorXd tr = Eigen::RowVectorXd::Zero(n_);
    for (const auto& e : row(cc.upper)) tr[e.first] += e.second;
    for (const auto& e : row(cc.lower)) tr[e.first] -= e.second;
    c.t = tr;
    c.g0 = cc.gap;
    c.law = ContactLaw::of(scene.contact, cc.e, std::nullopt, std::nullopt);
    contacts_.push_back(std::move(c));
  }
  if (shaft) attach_camshaft(scene, net, red, index);
  finish_contacts([&](const double* b, double* x) {
    Eigen::Map<Eigen::VectorXd>(x, n_) = Mldlt_.solve(Eigen::Map<const Eigen::VectorXd>(b, n_));
  });
  force_scale_ = f0_.size() ? f0_.cwiseAbs().maxCoeff() : 0.0;
  if (!elements_.empty()) {  // the elements' forces at q = 0 (their preloads)
    Eigen::VectorXd re = Eigen::VectorXd::Zero(n_), z = re;
    elements_.add_force(0.0, z.data(), z.data(), re.data(), s0_.data());
    force_scale_ = std::max(force_scale_, re.cwiseAbs().maxCoeff());
  }

  // ---- initial state: named nodes as given, inside nodes linear between their ends
  Eigen::VectorXd qf = Eigen::VectorXd::Zero(n_full), vf = qf;
  for (int i = 0; i < n_named; ++i) {
    qf[i] = net.nodes[i].initial_displacement;
    vf[i] = net.nodes[i].initial_velocity;
  }
  for (size_t k = 0; k < inner_ends.size(); ++k) {
    const int i = n_named + int(k), a = inner_ends[k].first, b = inner_ends[k].second;
    const double x = inner_frac[k];
    qf[i] = (1 - x) * (a >= 0 ? qf[a] : 0.0) + x * (b >= 0 ? qf[b] : 0.0);
    vf[i] = (1 - x) * (a >= 0 ? vf[a] : 0.0) + x * (b >= 0 ? vf[b] : 0.0);
  }
  q0_.resize(n_);
  v0_.resize(n_);
  for (int i = 0; i < n_full; ++i)
    if (red[i] >= 0) {
      q0_[red[i]] = qf[i];
      v0_[red[i]] = vf[i];
    }
  r0_ = f0_ - K_ * q0_;

  desc_.follower = "network";
  desc_.nodes = n_;
  desc_.unknowns = 2 * n_;
  desc_.mass = any_mass_matrix ? "consistent" : "lumped";
  desc_.sparse = true;
  desc_.linear_solver = scene.solver.integrator == Integrator::ArkodeErk
                            ? "none"
                            : (resolve_linear_solver(scene.solver, n_) == LinearSolverKind::Dense ? "dense" : "klu");
  desc_.damping = any_damping;
  desc_.preload = any_preload;
  desc_.contact = "unilateral × " + std::to_string(m());
  desc_.rhs_terms = {"inertia"};
  if (K_.nonZeros() > 0) desc_.rhs_terms.push_back("stiffness");
  if (any_preload) desc_.rhs_terms.push_back("preload");
  if (any_damping) desc_.rhs_terms.push_back("damping");
  if (!levers.empty()) desc_.rhs_terms.push_back("levers");
  if (!elements_.empty()) desc_.rhs_terms.push_back("nonlinear elements");
  desc_.rhs_terms.push_back("contacts");
}

bool Mechanism::acceleration_jacobian(double t, const double* q, const double* v, Eigen::MatrixXd& dadq,
                                      Eigen::MatrixXd& dadv) const {
  if (states() > 0) return false;  // the engines use the sparse Newton structure with the state blocks
  Eigen::MatrixXd K(K_), C = damped() ? Eigen::MatrixXd(C_) : Eigen::MatrixXd::Zero(n_, n_);
  if (!elements_.empty()) {
    SparseMatrix Ke, Ce;
    elements_.tangent(t, q, v, Ke, Ce);
    K += Eigen::MatrixXd(Ke);
    if (elements_.damps()) C += Eigen::MatrixXd(Ce);
  }
  dadq = -Mldlt_.solve(K);
  dadv = -Mldlt_.solve(C);
  return true;
}

std::vector<std::string> Mechanism::element_force_names() const {
  std::vector<std::string> n;
  for (const LinearForce& f : linear_forces_) n.push_back(f.name);
  for (const std::string& s : elements_.force_names()) n.push_back(s);
  return n;
}

void Mechanism::element_forces(double t, const double* q, const double* v, double* out, const double* s) const {
  auto dot = [](const std::vector<std::pair<int, double>>& r, const double* x) {
    double s = 0.0;
    for (const auto& e : r) s += e.second * x[e.first];
    return s;
  };
  for (const LinearForce& f : linear_forces_)
    *out++ = f.P + f.k * (dot(f.a, q) - dot(f.b, q)) + f.c * (dot(f.a, v) - dot(f.b, v));
  elements_.forces(t, q, v, out, s);
}

std::vector<std::string> Mechanism::surge_names() const {
  std::vector<std::string> n;
  for (const SurgeChain& s : surge_) n.push_back(s.name);
  return n;
}

void Mechanism::surge(const double* q, double* out) const {
  for (const SurgeChain& s : surge_) {
    double a = 0.0;
    for (const auto& r : s.rows) {
      double d = 0.0;
      for (const auto& e : r) d += e.second * q[e.first];
      a = std::max(a, std::abs(d));
    }
    *out++ = a;
  }
}

void Mechanism::factor_mass() {
  M_.makeCompressed();
  K_.makeCompressed();  // acceleration() walks K's and C's columns
  if (damped()) C_.makeCompressed();
  bool diag = true, tri = true;
  for (int j = 0; j < M_.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(M_, j); it; ++it) {
      if (it.value() == 0.0) continue;
      diag &= it.row() == j;
      tri &= std::abs(long(it.row()) - long(j)) <= 1;
    }
  const char* bad = "the mass matrix is not positive definite (a node without mass)";
  if (diag || tri) {  // LDLᵀ of a tridiagonal SPD matrix: no pivoting, no fill
    mass_dinv_.resize(n_);
    mass_l_ = Eigen::VectorXd::Zero(n_);
    double d_prev = 0.0;
    for (int j = 0; j < n_; ++j) {
      const double b = j > 0 && !diag ? M_.coeff(j, j - 1) : 0.0;
      if (j > 0) mass_l_[j] = b / d_prev;
      const double d = M_.coeff(j, j) - mass_l_[j] * b;
      if (!(d > 0.0)) throw std::invalid_argument(bad);
      mass_dinv_[j] = 1.0 / d;
      d_prev = d;
    }
    mass_pattern_ = diag ? MassPattern::Diagonal : MassPattern::Tridiagonal;
  }
  Mldlt_.compute(M_);  // also for the general pattern's callers (Jacobians)
  if (Mldlt_.info() != Eigen::Success || !(Mldlt_.vectorD().minCoeff() > 0.0)) throw std::invalid_argument(bad);
}

void Mechanism::solve_mass(Eigen::Ref<Eigen::VectorXd> x) const {
  switch (mass_pattern_) {
    case MassPattern::Diagonal:
      x.array() *= mass_dinv_.array();
      return;
    case MassPattern::Tridiagonal:
      for (int i = 1; i < n_; ++i) x[i] -= mass_l_[i] * x[i - 1];
      x[n_ - 1] *= mass_dinv_[n_ - 1];
      for (int i = n_ - 2; i >= 0; --i) x[i] = x[i] * mass_dinv_[i] - mass_l_[i + 1] * x[i + 1];
      return;
    case MassPattern::General:
      x = Mldlt_.solve(Eigen::VectorXd(x));
      return;
  }
}

void Mechanism::state_rate(double t, const double* q, const double* v, const double* s, double* sdot) const {
  elements_.state_rate(t, q, v, s, sdot);
}

void Mechanism::acceleration(double t, const double* q, const double* v, const Eigen::VectorXd& F, double* a,
                             bool homogeneous, const double* s) const {
  Eigen::Map<Eigen::VectorXd> A(a, n_);
  if (acceleration_kernel_ == AccelerationKernel::Assembled) {
    // f₀ − Kq − Cv and the sparse LDLᵀ, in this order (a penalty run at rtol 1e-4
    // is sensitive to the round-off of its forces: the two-mass train's energy residual
    // moved from 5.4e-4 to 1.2e-3 of the work with the one-pass form below).
    Eigen::Map<const Eigen::VectorXd> Q(q, n_), V(v, n_);
    Eigen::VectorXd r = -(K_ * Q);
    if (!homogeneous) r += f0_;
    if (damped()) r.noalias() -= C_ * V;
    if (!elements_.empty() && !homogeneous) elements_.add_force(t, q, v, r.data(), s);
    if (camshaft_) {  // the crank's part of the drive, the contacts' torques on the shaft
      if (!homogeneous) camshaft_->add_crank_forcing(t, r.data());
      if (F.size()) camshaft_->add_contact_torques(q, F.data(), int(F.size()), r.data());
    }
    A = Mldlt_.solve(r);
    if (F.size()) A.noalias() += MinvTt_ * F;
    return;
  }
  // Banded in place: one pass over K's columns (no temporaries), a = r₀ − K(q − q(0)) − Cv
  // (round-off scaling with the motion since t = 0), then M⁻¹ in place (diagonal or tridiagonal).
  const long* outer = K_.outerIndexPtr();
  const long* inner = K_.innerIndexPtr();
  const double* val = K_.valuePtr();
  if (homogeneous) A.setZero();
  else A = r0_;
  for (int j = 0; j < n_; ++j) {
    const double dq = homogeneous ? q[j] : q[j] - q0_[j];
    if (dq != 0.0)
      for (long p = outer[j]; p < outer[j + 1]; ++p) a[inner[p]] -= val[p] * dq;
  }
  if (damped()) {
    const long* co = C_.outerIndexPtr();
    const long* ci = C_.innerIndexPtr();
    const double* cv = C_.valuePtr();
    for (int j = 0; j < n_; ++j)
      if (v[j] != 0.0)
        for (long p = co[j]; p < co[j + 1]; ++p) a[ci[p]] -= cv[p] * v[j];
  }
  solve_mass(A);
  if (F.size() == 1)  // one contact: the product's own operations, without the matrix-vector kernel
    A.noalias() += MinvTt_.col(0) * F[0];
  else if (F.size())
    A.noalias() += MinvTt_ * F;
}

void Mechanism::contact_free_acceleration(double t, const double* q, const double* v, Eigen::VectorXd& Ta,
                                          const double* s) const {
  if (!traits_.linear_contact_acceleration) {
    MechanicalSystem::contact_free_acceleration(t, q, v, Ta, s);
    return;
  }
  Eigen::Map<const Eigen::VectorXd> Q(q, n_), V(v, n_);
  Ta = ta_r0_;
  Ta.noalias() -= ta_q_.transpose() * (Q - q0_);
  if (damped()) Ta.noalias() -= ta_v_.transpose() * V;
}

double Mechanism::kinetic_energy(const double* v) const {
  Eigen::Map<const Eigen::VectorXd> V(v, n_);
  return 0.5 * V.dot(M_ * V);
}
double Mechanism::potential_energy(const double* q, const double* s) const {
  Eigen::Map<const Eigen::VectorXd> Q(q, n_);
  double V = 0.5 * Q.dot(K_ * Q) - f0_.dot(Q) + (elements_.empty() ? 0.0 : elements_.stored_energy(q, s));
  if (camshaft_) V -= camshaft_->coupling_energy(q);  // the drive's couplings are the driver's (camshaft.hpp)
  return V;
}
double Mechanism::damping_power(const double* v) const {
  if (!damped()) return 0.0;
  Eigen::Map<const Eigen::VectorXd> V(v, n_);
  double P = V.dot(C_ * V);
  if (camshaft_) P -= camshaft_->coupling_dissipation(v);  // the drive's couplings' dampers are the driver's
  return P;
}
double Mechanism::input_power(double t, const double* q, const double* v) const {
  if (!camshaft_) return 0.0;
  return camshaft_->coupling_power(t, q, v);
}
double Mechanism::damping_power(double t, const double* q, const double* v, const double* s) const {
  double P = damping_power(v);
  if (!elements_.empty()) P += elements_.dissipated_power(t, q, v, s);
  return P;
}

}  // namespace camdyn
