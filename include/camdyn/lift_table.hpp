// camdyn — follower-lift tables in CSV: export from any cam, import with checks
// (docs/cam_laws.md "Lift tables").
#pragma once

#include <string>
#include <vector>

#include "camdyn/cam.hpp"

namespace camdyn {

/// A follower-lift table as other cam tools exchange it (docs/cam_laws.md "Lift tables"):
/// cam angles [deg] and the follower's lift L [length], optionally with dL/dθ
/// [length/deg] and d²L/dθ² [length/deg²] (both or neither).
struct LiftTable {
  std::vector<double> angle_deg, lift, dlift_ddeg, d2lift_ddeg2;
};

/// The follower's lift L(θ) = X_C(θ) − min_θ X_C of `cam` at `points` cam angles
/// 360° i / points, with its first two derivatives (exact for law, circle and arc cams).
/// @pre points ≥ 4.
LiftTable lift_table_of(const Cam& cam, int points);
/// The table as CSV: the header `angle_deg,lift` (`,dlift_ddeg,d2lift_ddeg2` when the
/// derivatives are given), then one row per angle in shortest round-trip form.
std::string lift_table_csv(const LiftTable& table);
/// Read a lift table from CSV text: lines starting with `#` and blank lines skipped; the
/// first other line is the header, `angle_deg,lift` or `angle_deg,lift,dlift_ddeg,d2lift_ddeg2`;
/// then one row per angle with that many numbers. @throws SceneError (file `source`, the
/// line, the column name as key) on a bad header, a short or long row, a number that does
/// not parse or is not finite, fewer than 4 rows, angles not strictly increasing or
/// spanning 360° or more.
LiftTable parse_lift_table_csv(const std::string& text, const std::string& source);
/// parse_lift_table_csv of the file at `path`. @throws SceneError (key cam.lift_table) when
/// the file cannot be read, and parse_lift_table_csv's errors (file `path`).
LiftTable read_lift_table_csv(const std::string& path);

}  // namespace camdyn
