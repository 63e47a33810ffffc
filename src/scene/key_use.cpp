// camdyn — which scene keys a run of a scene does not read (unused_key_reason).
#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/scene_keys.hpp"

namespace camdyn {

namespace {
bool in(const std::string& x, const std::vector<const char*>& set) {
  for (const char* s : set)
    if (x == s) return true;
  return false;
}
}  // namespace

std::string unused_key_reason(const Scene& s, const std::string& key) {
  const auto dot = key.find('.');
  if (dot == std::string::npos) return "";
  const std::string table = key.substr(0, dot), leaf = key.substr(dot + 1);
  const bool network = s.follower.kind == FollowerKind::Network;
  if (network && (table == "spring" || (table == "follower" && leaf != "kind")))
    return "is not used by a network follower (follower.kind = \"network\": its [[nodes]], [[elements]] and "
           "[[contacts]] replace [follower] and [spring]; sweep a network key, e.g. elements.NAME.stiffness)";
  if (s.follower.kind == FollowerKind::Rigid && table == "follower" &&
      in(leaf, {"youngs_modulus", "area", "length", "elements", "mass_matrix", "rayleigh_alpha", "rayleigh_beta"}))
    return "is not used by a rigid follower (follower.kind = \"rigid\"; the elastic bar's keys need "
           "follower.kind = \"elastic_bar\")";
  if (table == "cam") {
    struct ProfileKeys {
      CamProfileKind profile;
      std::vector<const char*> keys;
    };
    static const ProfileKeys kOwn[] = {
        {CamProfileKind::Circle, {"radius", "eccentricity"}},
        {CamProfileKind::Points, {"angles_deg", "radii"}},
        {CamProfileKind::Lift, {"lift_angles_deg", "lift"}},
        {CamProfileKind::Arc, {"nose_radius", "nose_distance", "flank_radius"}},
        {CamProfileKind::Law, {"law"}},
    };
    for (const ProfileKeys& p : kOwn)
      if (in(leaf, p.keys) && s.cam.profile != p.profile)
        return std::string("is not used by cam.profile = \"") + to_string(s.cam.profile) + "\" (it belongs to profile \"" +
               to_string(p.profile) + "\")";
  }
  if (table == "contact" && in(leaf, {"penalty_stiffness", "penalty_damping", "penalty_exponent", "penalty_law"}) &&
      s.contact.model != ContactModel::Penalty)
    return std::string("is not used by contact.model = \"") + to_string(s.contact.model) +
           "\" (the penalty law's keys need contact.model = \"penalty\")";
  return "";
}

}  // namespace camdyn
