// camdyn — a user's follower (include/camdyn/follower_system.hpp) as the MechanicalSystem the
// methods integrate (src/mechanism/mechanism.hpp: make_user_system).
#include <cmath>
#include <stdexcept>

#include "cam/format.hpp"  // detail::fmt
#include "mechanism/mechanism.hpp"

namespace camdyn {

namespace {
class UserMechanism final : public MechanicalSystem {
 public:
  UserMechanism(const Scene& scene, std::shared_ptr<const FollowerSystem> f) : f_(std::move(f)) {
    auto fail = [](const std::string& key, const std::string& value, const std::string& rule) {
      throw SceneError("<follower>", 0, key, value, rule);
    };
    n_ = f_->size();
    if (n_ < 1) fail("size()", std::to_string(n_), "must be >= 1");
    // A user follower is dense (its Jacobian is n × n, each factorisation n³): larger trains
    // are networks (sparse, KLU).
    constexpr int kMaxUserSize = 1000;
    if (n_ > kMaxUserSize)
      fail("size()", std::to_string(n_),
           "must be <= " + std::to_string(kMaxUserSize) +
               ": a user follower's Jacobian is dense (n² memory, n³ per factorisation); write a larger train as a "
               "network (follower.kind = \"network\", sparse)");
    const std::vector<FollowerContact> cs = f_->contacts();
    if (cs.empty()) fail("contacts()", "[]", "needs at least one contact");
    for (size_t i = 0; i < cs.size(); ++i) {
      const FollowerContact& c = cs[i];
      const std::string p = "contacts()[" + std::to_string(i) + "]";
      if (c.name.empty() || c.name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
        fail(p + ".name", "\"" + c.name + "\"", "must be non-empty, letters, digits, '_' and '-' only");
      for (size_t k = 0; k < i; ++k)
        if (cs[k].name == c.name) fail(p + ".name", "\"" + c.name + "\"", "must be unique");
      if (int(c.row.size()) != n_)
        fail(p + ".row", std::to_string(c.row.size()) + " entries", "must have size() = " + std::to_string(n_) + " entries");
      bool nonzero = false;
      for (double x : c.row) {
        if (!std::isfinite(x)) fail(p + ".row", "non-finite entry", "must be finite");
        nonzero |= x != 0.0;
      }
      if (!nonzero) fail(p + ".row", "all zero", "must not be all zero");
      if (!(c.clearance >= 0.0) || !std::isfinite(c.clearance))
        fail(p + ".clearance", detail::fmt(c.clearance), "must be finite and >= 0");
      if (c.restitution && !(*c.restitution >= 0.0 && *c.restitution <= 1.0))
        fail(p + ".restitution", detail::fmt(*c.restitution), "must be >= 0 and <= 1");
      if (c.penalty_stiffness && !(*c.penalty_stiffness > 0.0))
        fail(p + ".penalty_stiffness", detail::fmt(*c.penalty_stiffness), "must be > 0");
      if (c.penalty_damping && !(*c.penalty_damping >= 0.0))
        fail(p + ".penalty_damping", detail::fmt(*c.penalty_damping), "must be >= 0");
      MechanismContact m;
      m.name = c.name;
      m.kind = c.cam ? ContactPointKind::Cam : ContactPointKind::Stop;
      m.t = Eigen::Map<const Eigen::RowVectorXd>(c.row.data(), n_);
      m.g0 = c.clearance;
      m.cam = c.cam;
      m.law = ContactLaw::of(scene.contact, c.restitution, c.penalty_stiffness, c.penalty_damping);
      contacts_.push_back(std::move(m));
    }
    finish_contacts([&](const double* b, double* x) { f_->solve_mass(b, x); });
    if (!W_.allFinite() || W_.diagonal().minCoeff() <= 0.0)
      fail("solve_mass()", "T M⁻¹ Tᵀ", "must give a positive diagonal (M symmetric positive definite)");
    q0_.resize(n_);
    v0_.resize(n_);
    f_->initial_state(q0_.data(), v0_.data());
    // the force at rest: the scale of the force thresholds
    Eigen::VectorXd r(n_), zero = Eigen::VectorXd::Zero(n_);
    f_->force(0.0, q0_.data(), zero.data(), r.data());
    force_scale_ = r.cwiseAbs().maxCoeff();
    for (int i = 0; i < n_; ++i) node_names_.push_back("q" + std::to_string(i));
    L_.resize(n_, n_);
    L_.setIdentity();
    desc_.follower = "user: " + f_->name();
    desc_.nodes = n_;
    desc_.unknowns = 2 * n_;
    desc_.mass = "user (M⁻¹ action)";
    desc_.linear_solver = scene.solver.integrator == Integrator::ArkodeErk ? "none" : "dense";
    desc_.contact = "unilateral × " + std::to_string(m());
    Eigen::MatrixXd dq, dv;
    const bool jac = f_->force_jacobian(0.0, q0_.data(), v0_.data(), (dq = Eigen::MatrixXd(n_, n_)).data(),
                                        (dv = Eigen::MatrixXd(n_, n_)).data());
    desc_.rhs_terms = {"inertia", "user force r(t, q, v)", jac ? "user Jacobian" : "difference-quotient Jacobian",
                       "contacts"};
    for (const MechanismContact& c : contacts_)
      desc_.network.push_back("contact '" + c.name + "' (" + (c.cam ? "cam" : "stop") + ", clearance " +
                              detail::fmt(c.g0) + ", e " + detail::fmt(c.law.impact.restitution) + ")");
  }
  bool linear() const override { return f_->linear(); }
  void acceleration(double t, const double* q, const double* v, const Eigen::VectorXd& F, double* a,
                    bool homogeneous, const double* /*s: none*/) const override {
    r_.resize(n_);
    f_->force(t, q, v, r_.data());
    // A non-finite force is named here (the engine would only see its step size collapse).
    for (int i = 0; i < n_; ++i)
      if (!std::isfinite(r_[i]))
        throw std::runtime_error("the follower's force(t, q, v) returned a non-finite value at t = " +
                                 std::to_string(t) + ": entry " + std::to_string(i) + " is " +
                                 (std::isnan(r_[i]) ? "nan" : r_[i] > 0 ? "inf" : "-inf"));
    if (homogeneous) {  // linear only: drop r's constant part r(t, 0, 0)
      Eigen::VectorXd z = Eigen::VectorXd::Zero(n_), r0(n_);
      f_->force(t, z.data(), z.data(), r0.data());
      r_ -= r0;
    }
    if (F.size()) r_.noalias() += T_.transpose() * F;
    f_->solve_mass(r_.data(), a);
  }
  bool acceleration_jacobian(double t, const double* q, const double* v, Eigen::MatrixXd& dadq,
                             Eigen::MatrixXd& dadv) const override {
    Eigen::MatrixXd drdq(n_, n_), drdv(n_, n_);
    if (!f_->force_jacobian(t, q, v, drdq.data(), drdv.data())) return false;
    dadq.resize(n_, n_);
    dadv.resize(n_, n_);
    for (int j = 0; j < n_; ++j) {
      f_->solve_mass(drdq.col(j).data(), dadq.col(j).data());
      f_->solve_mass(drdv.col(j).data(), dadv.col(j).data());
    }
    return true;
  }
  double kinetic_energy(const double* v) const override { return f_->kinetic_energy(v); }
  double potential_energy(const double* q, const double*) const override { return f_->potential_energy(q); }
  double damping_power(double, const double*, const double* v, const double*) const override {
    return f_->damping_power(v);
  }

 private:
  std::shared_ptr<const FollowerSystem> f_;
  mutable Eigen::VectorXd r_;
};
}  // namespace

std::shared_ptr<const MechanicalSystem> make_user_system(const Scene& scene,
                                                         std::shared_ptr<const FollowerSystem> follower) {
  if (!follower) throw std::invalid_argument("Simulator: the follower is null");
  return std::make_shared<const UserMechanism>(scene, std::move(follower));
}

}  // namespace camdyn
