// camdyn — what a run reports as it goes: the history rows (history.csv) and the contact
// events (events.csv).
#pragma once

#include <string>
#include <vector>

namespace camdyn {

/// One output row (docs/interface.md history.csv, then energy columns).
struct HistoryRow {
  double t = 0, theta = 0, u_c = 0, v_c = 0, a_c = 0;
  double contact_force = 0;  ///< −p ≥ 0
  double gap = 0;            ///< −s: ≥ 0 apart, < 0 penetration
  int in_contact = 0;
  double kinetic = 0;        ///< ½ vᵀ M v
  double potential = 0;      ///< strain + spring energy change since t = 0
  double work_cam = 0;       ///< ∫ F v₀ dt, work done by the cam on the follower
  double dissipated = 0;     ///< ∫ vᵀ C v dt + energy lost in impacts
  /// Network scenes and user followers: per contact (F_<name>, gap_<name>, in_<name>), then
  /// per named node (u_<name>, v_<name>); then, with run.designer_columns, the six designer
  /// columns (pressure_angle_deg, radius_of_curvature, contact_stress, side_load, cam_torque,
  /// cam_power); in the order of Simulator::extra_columns(); empty otherwise.
  std::vector<double> extra;
};

/// Names of the history columns, in order.
const std::vector<std::string>& history_columns();

/// Whether a run's extra history columns (Simulator::extra_columns()) begin with its
/// contacts' own columns F_<name>, gap_<name>, in_<name>: a network or a user follower,
/// whose contacts have names. Its events then carry their contact's name (events.csv's last
/// column `contact`); the one contact of a rigid or elastic_bar follower has no name, and
/// its designer, oil-film and friction columns are no contact's.
bool has_named_contacts(const std::vector<std::string>& extra_columns);

/// What a contact event is (ContactEvent::type).
enum class EventKind {
  Impact,      ///< the contact closes with an approach velocity
  Separation,  ///< the contact opens
  Tensile,     ///< holonomic contact: the constraint force starts to pull (first time)
};
/// "impact", "separation", "tensile" (events.csv's `kind` column).
const char* to_string(EventKind k);

/// A contact event.
struct ContactEvent {
  double t = 0;
  double impact_velocity = 0;   ///< relative approach velocity (impacts), else 0
  double theta = 0;             ///< cam angle at the event [rad] (as history.csv's theta)
  double impulse = 0;           ///< contact impulse applied at the instant (impacts resolved
                                ///< as a Newton impulse: event-driven, Lee "located"), else 0
  std::string contact;          ///< network scenes and user followers: the contact's name ("" otherwise)
  EventKind type = EventKind::Impact;  ///< what the event is (to_string(type): events.csv's kind)
};

}  // namespace camdyn
