// camdyn (private) — the mechanism every follower runs as: M, C, K, f₀ and one contact row
// per contact; assembled here from a network scene (include/camdyn/network.hpp,
// docs/interface.md "Networks"), from a rigid or elastic_bar follower by follower_builder.cpp.
//
//   M q̈ + C q̇ + K q = f₀ + Tᵀ F,     F ≥ 0 (one entry per contact)
//   gap of contact j:  g_j = T_j q + g₀_j − X_C(t)·[j touches the cam]
//
//   Assembly over the network's nodes (ground dropped), then levers eliminated:
//     q_full = L q  (a lever's output node is ratio × its input node, plus (1 − ratio) × its
//     pivot node on a moving pivot; chains resolved),
//     M = LᵀM_f L, C = LᵀC_f L, K = LᵀK_f L, f₀ = Lᵀf₀_f, T = T_f L.
//   spring [a, b] (δ = q_a − q_b):  K_f += k[1 −1; −1 1], C_f += c[…], f₀_f += P(−e_a + e_b)
//   spring with mass m_s, N masses: N + 1 springs of (N + 1)k (and (N + 1)c) in series,
//     masses m_s/(N + 1) inside, m_s/(2(N + 1)) added on each end node (a lumped bar).
//   bar (N elements, h = L/N, mₑ = m/N): Kₑ = EA/h[1 −1; −1 1], Mₑ = mₑ/6[2 1; 1 2] or
//     mₑ/2 I, C += αMₑ + βKₑ.
//   W = T M⁻¹ Tᵀ (m × m): the contacts' inverse mass matrix (Lee's M* for several contacts).
//
// M, C, K, L are sparse (CSC): a valve train has a handful of unknowns, a pushrod meshed
// finely 10⁵ (issue 23: memory and work per step linear in the unknowns). M⁻¹ acts through
// one sparse LDLᵀ factorisation of M (no fill for a chain); the implicit engines solve
// their Newton systems through the sparse Schur complement M + γC + γ²K (ode_engine.hpp,
// SparseNewton). Only what the scene asks for is built (C only if some element damps; the
// description lists the assembled network).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/follower_system.hpp"
#include "mechanism/sparse_matrix.hpp"
#include "camdyn/model_description.hpp"
#include "camdyn/scene.hpp"
#include "contact/laws/contact_law.hpp"
#include "mechanism/element_set.hpp"
#include "mechanism/camshaft.hpp"

namespace camdyn {

/// One contact of a mechanism: a row of T.
struct MechanismContact {
  std::string name;
  ContactPointKind kind = ContactPointKind::Cam;
  Eigen::RowVectorXd t;  ///< row of T over the unknowns
  double g0 = 0.0;       ///< gap at q = 0 (and X_C = 0)
  bool cam = false;      ///< the cam's lift X_C(t) enters the gap
  ContactLaw law;        ///< its impact and penalty laws (scene values, [contact] as defaults)
  /// A coil-to-coil contact of a spring whose coils clash: the spring's report name ("" for
  /// the scene's own contacts).
  std::string coil_spring;
};

/// What the contact methods integrate: M q̈ = r(t, q, q̇) + TᵀF with constant M and contact
/// rows T. Two kinds: the linear Mechanism assembled from a network scene, and a user's
/// FollowerSystem (include/camdyn/follower_system.hpp) through an adapter.
/// What a mechanism is, for the parts that run and record it: set once by the builder that
/// makes it (the defaults are a network's and a user FollowerSystem's; a rigid or
/// elastic_bar follower's builder, src/mechanism/follower_builder.cpp, sets its own), so no
/// method, engine or output asks which scene kind produced it.
struct MechanismTraits {
  /// Its contacts and nodes are named (history columns F_/gap_/in_<contact>, u_/v_<node>,
  /// element results, the verdict's contacts); false: one unnamed cam contact that the
  /// history's standard columns show.
  bool named_contacts = true;
  /// The cam contact's gap sees the cam's X_C itself (g = q₀ − X_C, u_c = q₀); false: the
  /// lift above the base circle, X_C − X_base.
  bool cam_lift_absolute = false;
  /// One body on one axis: the uniform shift of every unknown is its rigid translation (the
  /// direction of a held contact's static correction).
  bool one_body = false;
  /// An elastic body whose internal modes are stiff against the contact's time scale: BDF
  /// order ≤ 2 at loose tolerances, and a projection that moves the rigid translation
  /// (metric γ = 10⁶·h) (methods/event.cpp).
  bool stiff_internal_modes = false;
  /// T a_free is a linear form in (q, q̇) stored with the mechanism: a contact's free
  /// acceleration costs O(n), no mass solve (contact_free_acceleration).
  bool linear_contact_acceleration = false;
  /// IDA's largest BDF order on this mechanism.
  int ida_max_order = 4;
};

class MechanicalSystem {
 public:
  virtual ~MechanicalSystem() = default;
  int n() const { return n_; }  ///< unknowns
  int m() const { return int(contacts_.size()); }
  const Eigen::MatrixXd& MinvTt() const { return MinvTt_; }  ///< M⁻¹Tᵀ (n × m)
  const Eigen::MatrixXd& T() const { return T_; }            ///< m × n
  const Eigen::MatrixXd& W() const { return W_; }            ///< T M⁻¹ Tᵀ
  const std::vector<MechanismContact>& contacts() const { return contacts_; }
  /// The contact shown in history.csv's standard columns: the first cam contact (or 0).
  int primary() const { return primary_; }
  int cam_contacts() const {
    int k = 0;
    for (const MechanismContact& c : contacts_) k += c.cam;
    return k;
  }
  /// Named nodes and their displacement q_node = L_row · q.
  const std::vector<std::string>& node_names() const { return node_names_; }
  const SparseMatrix& L() const { return L_; }  ///< named nodes × unknowns
  const Eigen::VectorXd& q0() const { return q0_; }
  const Eigen::VectorXd& v0() const { return v0_; }
  const ModelDescription& description() const { return desc_; }
  /// A typical force (thresholds): the largest preload.
  double force_scale() const { return force_scale_; }
  /// What the mechanism is, as the methods, engines and outputs need to know it (set once
  /// by its builder: MechanismTraits).
  const MechanismTraits& traits() const { return traits_; }

  /// true: r affine in (q, q̇) with constant coefficients (Lee's step map is affine).
  virtual bool linear() const = 0;
  /// The elements' internal states s (element.hpp): their count (0: none, and every `s`
  /// argument below may be null) and s(0). The methods carry them after q and v,
  /// y = [q; v; s], and pass y + 2n as `s`; impacts and projections leave them unchanged.
  int states() const { return int(s0_.size()); }
  const Eigen::VectorXd& s0() const { return s0_; }
  /// ṡ = g(t, q, v, s) (states() entries). Default: none.
  virtual void state_rate(double /*t*/, const double* /*q*/, const double* /*v*/, const double* /*s*/,
                          double* /*sdot*/) const {}
  /// a = M⁻¹(r(t, q, v, s) + TᵀF) (F over all contacts, or empty); homogeneous (linear only):
  /// without r's constant part.
  virtual void acceleration(double t, const double* q, const double* v, const Eigen::VectorXd& F,
                            double* a, bool homogeneous = false, const double* s = nullptr) const = 0;
  /// ∂a/∂q, ∂a/∂v without contacts (n × n, dense: for small systems; a Mechanism's
  /// engines use its sparse M, C, K instead); false if not available.
  virtual bool acceleration_jacobian(double t, const double* q, const double* v, Eigen::MatrixXd& dadq,
                                     Eigen::MatrixXd& dadv) const = 0;
  /// T a_free: the contacts' accelerations without contact forces, T M⁻¹ r(t, q, v)
  /// (m entries). Default: acceleration() then T·a.
  virtual void contact_free_acceleration(double t, const double* q, const double* v, Eigen::VectorXd& Ta,
                                         const double* s = nullptr) const {
    Eigen::VectorXd a(n_);
    acceleration(t, q, v, Eigen::VectorXd(), a.data(), false, s);
    Ta = T_ * a;
  }
  virtual double kinetic_energy(const double* v) const = 0;
  /// Up to a constant (with the elements' stored energy at their states s).
  virtual double potential_energy(const double* q, const double* s = nullptr) const = 0;
  /// The power dissipated inside the mechanism (not at its contacts) at (t, q, v, s).
  virtual double damping_power(double t, const double* q, const double* v, const double* s = nullptr) const = 0;
  /// The elements' reported forces (history columns force_<name>, run.element_forces): their
  /// names, and their values at (t, q, v) (element_force_names().size() entries). Default:
  /// none.
  virtual std::vector<std::string> element_force_names() const { return {}; }
  /// The springs with coil masses (their report names) and, at q, each one's surge: the
  /// largest |x_i − x_i,static| over its inner masses, x_i,static the linear interpolation of
  /// its two ends (surge_names().size() entries). Default: none.
  virtual std::vector<std::string> surge_names() const { return {}; }
  virtual void surge(const double* /*q*/, double* /*out*/) const {}
  virtual void element_forces(double /*t*/, const double* /*q*/, const double* /*v*/, double* /*out*/,
                              const double* /*s*/ = nullptr) const {}
  /// false: damping_power is zero for every v (a quadrature of it may skip the state).
  virtual bool dissipative() const { return true; }
  /// The camshaft of a [camshaft] scene (src/mechanism/camshaft.hpp), null without one: its
  /// cam contacts' gaps and rows depend on the shaft angle.
  const CamShaft* camshaft() const { return camshaft_.get(); }
  /// The power the driver feeds in at (t, q, v) (a camshaft's drive coupling, τ_d φ̇_d); 0
  /// without a camshaft (the prescribed cam's work is the contacts' F Ẋ_C).
  virtual double input_power(double /*t*/, const double* /*q*/, const double* /*v*/) const { return 0.0; }

 protected:
  /// T_, MinvTt_ (through solve), W_, primary_ from contacts_.
  template <class Solve>
  void finish_contacts(Solve solve) {
    T_.resize(m(), n_);
    for (int j = 0; j < m(); ++j) T_.row(j) = contacts_[j].t;
    MinvTt_.resize(n_, m());
    for (int j = 0; j < m(); ++j) {
      const Eigen::VectorXd b = T_.row(j).transpose();
      Eigen::VectorXd x(n_);
      solve(b.data(), x.data());
      MinvTt_.col(j) = x;
    }
    W_ = T_ * MinvTt_;
    primary_ = 0;
    for (int j = 0; j < m(); ++j)
      if (contacts_[j].cam) {
        primary_ = j;
        break;
      }
  }
  int n_ = 0, primary_ = 0;
  Eigen::MatrixXd MinvTt_, T_, W_;
  SparseMatrix L_;
  Eigen::VectorXd q0_, v0_, s0_;
  std::vector<MechanismContact> contacts_;
  std::vector<std::string> node_names_;
  ModelDescription desc_;
  double force_scale_ = 0.0;
  MechanismTraits traits_;
  std::shared_ptr<const CamShaft> camshaft_;
};

/// The linear mechanism of a scene (a network, or a rigid / elastic_bar follower): r = f₀ − Kq − Cq̇.
class Mechanism final : public MechanicalSystem {
 public:
  /// The mechanism of a scene: its network, or a rigid / elastic_bar follower as a
  /// one-contact mechanism (src/mechanism/follower_builder.cpp).
  /// @pre validate(scene) passed.
  /// @throws std::invalid_argument on a mass matrix that is not positive definite.
  explicit Mechanism(const Scene& scene);

  const SparseMatrix& M() const { return M_; }
  const SparseMatrix& K() const { return K_; }
  const SparseMatrix& C() const { return C_; }  ///< zero-sized if undamped
  bool damped() const { return C_.size() > 0; }
  const Eigen::VectorXd& f0() const { return f0_; }

  /// true without nonlinear elements and without cams on a camshaft's unknowns (a cam on a
  /// prescribed drive station is a prescribed cam).
  bool linear() const override { return elements_.empty() && (!camshaft_ || !camshaft_->rows_depend_on_state()); }
  void acceleration(double t, const double* q, const double* v, const Eigen::VectorXd& F, double* a,
                    bool homogeneous = false, const double* s = nullptr) const override;
  void state_rate(double t, const double* q, const double* v, const double* s, double* sdot) const override;
  bool acceleration_jacobian(double t, const double* q, const double* v, Eigen::MatrixXd& dadq,
                             Eigen::MatrixXd& dadv) const override;
  /// traits().linear_contact_acceleration: z_jᵀr₀ − (K z_j)ᵀ(q − q(0)) − (C z_j)ᵀv with
  /// z_j = M⁻¹T_jᵀ, O(n) without a mass solve; otherwise the default.
  void contact_free_acceleration(double t, const double* q, const double* v, Eigen::VectorXd& Ta,
                                 const double* s = nullptr) const override;
  double kinetic_energy(const double* v) const override;
  /// ½qᵀKq − f₀ᵀq (up to a constant).
  double potential_energy(const double* q, const double* s = nullptr) const override;
  double damping_power(double t, const double* q, const double* v, const double* s = nullptr) const override;
  bool dissipative() const override { return damped() || elements_.dissipates(); }
  /// A camshaft's drive power τ_d φ̇_d (camshaft.hpp); 0 without one.
  double input_power(double t, const double* q, const double* v) const override;
  /// Springs' and dashpots' P + kδ + cδ̇ (springs without mass), then the nonlinear elements'.
  std::vector<std::string> element_force_names() const override;
  void element_forces(double t, const double* q, const double* v, double* out,
                      const double* s = nullptr) const override;
  std::vector<std::string> surge_names() const override;
  void surge(const double* q, double* out) const override;
  /// The nonlinear elements (empty for a linear mechanism).
  const ElementSet& elements() const { return elements_; }

 private:
  /// A rigid or elastic_bar follower: its M, C, K, f₀ and q(0) (follower_matrices.hpp),
  /// contact row e₀ᵀ (follower_builder.cpp).
  void build_follower(const Scene& scene);
  /// After M_, K_, C_, f0_, q0_: the LDLᵀ of M and the shifted force origin.
  void factor_and_origin();
  /// The linear part's damping power vᵀCv.
  double damping_power(const double* v) const;
  SparseMatrix M_, K_, C_;
  ElementSet elements_;
  struct LinearForce {  // a spring's or dashpot's reported force
    std::string name;
    std::vector<std::pair<int, double>> a, b;  // its ends' rows of Lf: (reduced DOF, coefficient)
    double k, c, P;
  };
  std::vector<LinearForce> linear_forces_;
  struct SurgeChain {  // a spring with coil masses: per inner mass, its row x_i − x_i,static
    std::string name;
    std::vector<std::vector<std::pair<int, double>>> rows;
  };
  std::vector<SurgeChain> surge_;
  Eigen::SimplicialLDLT<SparseMatrix> Mldlt_;
  Eigen::VectorXd f0_;
  // r = f₀ − Kq − Cq̇ is evaluated as r₀ − K(q − q(0)) − Cq̇ with r₀ = f₀ − Kq(0): the same
  // value, with round-off that scales with the motion since t = 0, not with |K||q| (a stiff
  // bar at rest otherwise shows force noise of ~1e-7 of its preload).
  Eigen::VectorXd r0_;
  /// x ← M⁻¹x in place: diagonal M by its inverse diagonal, tridiagonal M (a chain: the
  /// single bar) by two O(n) passes of its LDLᵀ, any other pattern by the sparse LDLᵀ.
  void solve_mass(Eigen::Ref<Eigen::VectorXd> x) const;
  void factor_mass();  // after M_: picks the solve above; @throws std::invalid_argument
  // A [camshaft]: the CamShaft of the built mechanism (mechanism_camshaft.cpp). red: full
  // DOF → unknown; index: named node → full DOF.
  void attach_camshaft(const Scene& scene, const NetworkSpec& net, const std::vector<int>& red,
                       const std::map<std::string, int>& index);
  enum class MassPattern { Diagonal, Tridiagonal, General } mass_pattern_ = MassPattern::General;
  /// acceleration()'s kernel, chosen by the builder. Assembled: r = f₀ − Kq − Cq̇ (+ the
  /// elements' and the camshaft's forces), then the sparse LDLᵀ. BandedInPlace: r₀ −
  /// K(q − q(0)) − Cq̇ in one pass over K's and C's columns, then M⁻¹ in place by
  /// solve_mass; for a diagonal or tridiagonal M, without elements and camshaft (it adds
  /// neither's forces).
  enum class AccelerationKernel { Assembled, BandedInPlace } acceleration_kernel_ = AccelerationKernel::Assembled;
  Eigen::VectorXd mass_dinv_, mass_l_;  // 1/D, and L's subdiagonal (tridiagonal)
  // contact_free_acceleration's linear forms (traits_.linear_contact_acceleration): z_jᵀr₀, K z_j, C z_j
  Eigen::VectorXd ta_r0_;
  Eigen::MatrixXd ta_q_, ta_v_;
};

/// An element's name in reports and history columns: its scene name, or "<kind>_<index>".
std::string element_report_name(const ElementSpec& e, std::size_t index);

/// A user's follower as the system the contact methods integrate (src/mechanism/user_mechanism.cpp).
/// @throws SceneError (file "<follower>") naming the offending contact field.
std::shared_ptr<const MechanicalSystem> make_user_system(const Scene& scene,
                                                         std::shared_ptr<const FollowerSystem> follower);

}  // namespace camdyn
