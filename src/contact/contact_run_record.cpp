// camdyn — the recorder of a contact run (contact_run.hpp): the history columns, the rows
// (state, forces, energies, the named contacts' and nodes' columns, designer and
// analysis columns), the events, and the per-contact statistics they feed.
#include <algorithm>
#include <cmath>

#include "contact/contact_run.hpp"
#include "mechanism/element_set.hpp"

namespace camdyn {
namespace detail {

namespace {
constexpr double kFloatLift = 0.01;  // a float: the cam above clearance + 1 % of its lift
}  // namespace

std::vector<std::string> ContactRun::extra_columns(const MechanicalSystem& mech, bool element_forces) {
  std::vector<std::string> c;
  if (!mech.traits().named_contacts) return c;  // the standard columns show its one contact
  for (const MechanismContact& k : mech.contacts()) {
    c.push_back("F_" + k.name);
    c.push_back("gap_" + k.name);
    c.push_back("in_" + k.name);
  }
  for (const std::string& nd : mech.node_names()) {
    c.push_back("u_" + nd);
    c.push_back("v_" + nd);
  }
  if (element_forces) {
    for (const std::string& f : mech.element_force_names()) c.push_back("force_" + f);
    for (const std::string& f : mech.surge_names()) c.push_back("surge_" + f);
  }
  if (const CamShaft* cs = mech.camshaft()) {  // the drive and each cam's wind-up
    c.push_back("drive_torque");
    c.push_back("drive_twist");
    for (int i = 0; i < cs->cams(); ++i) c.push_back("windup_cam" + std::to_string(i));
  }
  return c;
}

void ContactRun::emit_row() { emit_row_at(t_, y_, F_, active_, work_, dissipated_); }

void ContactRun::emit_row_at(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& F,
                             const std::vector<char>& active, double W, double D) {
  const int p = mk_.primary();
  const CamMotion cm = cam_at(t);
  Eigen::VectorXd a;
  acceleration(t, y, F, a);
  const MechanismContact& c = mk_.contacts()[p];
  HistoryRow r;
  r.t = t;
  r.theta = drive_.theta(t);
  r.u_c = c.t.dot(y.head(n_)) + c.g0;
  r.v_c = c.t.dot(y.segment(n_, n_));
  r.a_c = c.t.dot(a);
  r.contact_force = F[p];
  r.gap = gap(p, y, cm);
  r.in_contact = active[p] ? 1 : 0;
  r.kinetic = mk_.kinetic_energy(y.data() + n_);
  r.potential = potential(t, y) - V0_;
  r.work_cam = W;
  r.dissipated = D;
  r.extra.reserve(3 * m_ + 2 * mk_.node_names().size());
  for (int j = 0; j < m_ && mk_.traits().named_contacts; ++j) {
    r.extra.push_back(F[j]);
    r.extra.push_back(gap(j, y, cm));
    r.extra.push_back(active[j] ? 1.0 : 0.0);
  }
  const Eigen::VectorXd u = mk_.L() * y.head(n_), v = mk_.L() * y.segment(n_, n_);
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    r.extra.push_back(u[i]);
    r.extra.push_back(v[i]);
  }
  if (sc_.run.element_forces && mk_.traits().named_contacts) {
    const std::size_t k = r.extra.size();
    r.extra.resize(k + element_force_count_);
    mk_.element_forces(t, y.data(), y.data() + n_, r.extra.data() + k, states_of(y));
    r.extra.resize(k + element_force_count_ + surge_buf_.size());
    mk_.surge(y.data(), r.extra.data() + k + element_force_count_);
  }
  if (const CamShaft* cs = mk_.camshaft()) {
    const int d = cs->drive_station();
    double th = 0.0, w = 0.0;
    cs->crank(t, &th, &w);
    const double phi_d = cs->station_angle(d, t, y.data());
    r.extra.push_back(cs->drive_torque(t, y.data(), y.data() + n_, F.data(), m_));
    r.extra.push_back(th - phi_d);
    for (int i = 0; i < cs->cams(); ++i) r.extra.push_back(phi_d - cs->station_angle(cs->cam_station(i), t, y.data()));
  }
  if (sc_.run.designer_columns) {
    double Fc = 0.0;  // the cam's force: Σ over the cam contacts (their axial components)
    const CamShaft* cs = mk_.camshaft();
    const int pc = cs ? cs->contact_cam(p) : -1;
    if (pc >= 0) {  // a camshaft: the primary contact's cam at its own angle and speed, its contacts' force
      for (int j = 0; j < m_; ++j)
        if (cs->contact_cam(j) == pc) Fc += F[j];
      const int st = cs->cam_station(pc);
      design_cols_.append(cam_.evaluate(cs->cam_angle(pc, t, y.data())), Fc, cs->station_speed(st, t, y.data() + n_),
                          r.extra);
    } else {
      for (int j = 0; j < m_; ++j)
        if (mk_.contacts()[j].cam) Fc += F[j];
      design_cols_.append(cam_.evaluate(r.theta), Fc, drive_.omega(t), r.extra);
    }
  }
  if (analysis_.per_row()) {
    double Fc = 0.0;
    for (int j = 0; j < m_; ++j)
      if (mk_.contacts()[j].cam) Fc += F[j];
    row_gaps_.resize(std::size_t(m_));
    for (int j = 0; j < m_; ++j) row_gaps_[std::size_t(j)] = gap(j, y, cm);
    row_u_.assign(u.data(), u.data() + u.size());
    const CamPoint pt = sc_.lubricant.viscosity > 0 ? cam_.evaluate(r.theta) : CamPoint{};
    analysis_.row(t, r.theta, pt, cm.X, cm.Xdot, drive_.omega(t), Fc, row_gaps_, row_u_, r.extra);
  }
  if (design_cols_.friction()) {
    double Fc = 0.0;
    for (int j = 0; j < m_; ++j)
      if (mk_.contacts()[j].cam) Fc += F[j];
    design_cols_.append_friction(cam_.evaluate(r.theta), Fc, drive_.omega(t), r.extra);
  }
  if (!traced_ && !in_take_up(t))
    for (int j = 0; j < m_; ++j)
      if (active[j]) sample_contact(j, F[j], angle_deg_mod360(r.theta));
  last_row_t_ = t;
  if (obs_ && obs_->on_output(r) == ObserverAction::Stop) observer_stop_ = true;
}

void ContactRun::record_event(EventKind type, int contact, double v, double impulse, double t_event) {
  const double te = std::isnan(t_event) ? t_ : t_event;
  // a camshaft's cam contact: the angle of its own cam, its station's angle − its offset (the
  // state's: events are recorded at the state they happen at)
  const CamShaft* shaft = mk_.camshaft();
  const double theta = shaft && shaft->contact_cam(contact) >= 0
                           ? shaft->cam_angle(shaft->contact_cam(contact), te, y_.data())
                           : drive_.theta(te);
  ContactEvent e{te, v, theta, impulse, mk_.contacts()[contact].name, type};
  // The designer results follow the primary contact (the cam's). A cam contact with lash
  // opens at the end of every lift event as the cam returns to its base circle, a few µm
  // above the clearance (the chain's deflection under load): only a separation while the
  // cam is lifted past the clearance by more than kFloatLift of its lift is a float (a
  // jump: first_separation_theta_deg, camdyn jump).
  if (contact == mk_.primary()) {
    const MechanismContact& c = mk_.contacts()[contact];
    const CamShaft* cs = mk_.camshaft();
    const double X = cs && cs->contact_cam(contact) >= 0 ? cs->lift(contact, te, y_.data()).X : cam_at(te).X;
    const bool on_lift = !c.cam || X > c.g0 + kFloatLift * cam_.lift();
    if (e.type != EventKind::Separation || on_lift) designer_.event(e);
  }
  rec_.events.push_back(e);
  analysis_.event(e, contact);
  flights_.event(type, contact, te, v);
  ContactResult& cr = rec_.contacts[contact];
  const double th = angle_deg_mod360(e.theta);
  if (type == EventKind::Separation) {
    ++cr.separations;
    if (std::isnan(cr.first_separation_theta_deg)) cr.first_separation_theta_deg = th;
    if (!in_take_up(te)) sample_contact(contact, 0.0, th);
  } else if (type == EventKind::Impact) {
    ++cr.impacts;
    if (std::isnan(cr.first_impact_theta_deg)) cr.first_impact_theta_deg = th;
    if (std::isnan(cr.max_impact_theta_deg) || v > cr.max_impact_velocity) {
      cr.max_impact_velocity = v;
      cr.max_impact_theta_deg = th;
    }
  }
  if (obs_) obs_->on_event(e);
}

void ContactRun::sample_side_loads(double theta, const CamPoint* cp) {
  bool any = false;
  for (int j = 0; j < m_ && !any; ++j) any = mk_.contacts()[j].cam && active_[j];
  if (!any) return;
  const double tan_phi = std::tan((cp ? *cp : cam_.evaluate(theta)).pressure_angle);
  for (int j = 0; j < m_; ++j) {
    if (!mk_.contacts()[j].cam || !active_[j]) continue;
    ContactResult& cr = rec_.contacts[j];
    const double side = std::abs(F_[j] * tan_phi);
    if (std::isnan(cr.max_side_load) || side > cr.max_side_load) {
      cr.max_side_load = side;
      cr.max_side_load_theta_deg = angle_deg_mod360(theta);
    }
  }
}

bool ContactRun::in_take_up(double t) const {
  if (std::isnan(take_up_lo_)) return false;
  const double X = cam_at(t).X;
  return X >= take_up_lo_ && X <= take_up_hi_;
}

void ContactRun::sample_held_force(int j, double t, double F) {
  const double th = drive_.theta(t);
  if (!in_take_up(t)) sample_contact(j, F, angle_deg_mod360(th));
  if (j == mk_.primary()) designer_.sample_force(t, th, F);
}

void ContactRun::sample_contact(int j, double F, double theta_deg) {
  ContactResult& cr = rec_.contacts[j];
  if (std::isnan(cr.min_force) || F < cr.min_force) {
    cr.min_force = std::max(F, 0.0);
    cr.min_force_theta_deg = theta_deg;
  }
}

void ContactRun::sample_elements() {
  if (!element_results_) return;
  mk_.element_forces(t_, y_.data(), y_.data() + n_, element_buf_.data(), states_of(y_));
  const double turn = std::abs(drive_.theta(t_) - drive_.theta(0.0)) / (2.0 * M_PI);
  const long rev = long(std::floor(turn * (1 + 1e-12)));
  const bool new_rev = element_rev_ >= 0 && rev != element_rev_;
  for (std::size_t i = 0; i < element_force_count_; ++i) {
    ElementResult& r = rec_.elements[i];
    const double x = element_buf_[i];
    r.min = std::isnan(r.min) ? x : std::min(r.min, x);
    r.max = std::isnan(r.max) ? x : std::max(r.max, x);
    r.end = x;
    element_cyc_min_[i] = std::min(element_cyc_min_[i], x);
    element_cyc_max_[i] = std::max(element_cyc_max_[i], x);
    if (new_rev) {  // a revolution completed at this sample
      r.cycle_range = element_cyc_max_[i] - element_cyc_min_[i];
      element_cyc_min_[i] = element_cyc_max_[i] = x;
    }
  }
  element_rev_ = rev;
}

}  // namespace detail
}  // namespace camdyn
