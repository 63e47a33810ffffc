// camdyn — the cam's enumerations as strings (camdyn/cam_spec.hpp).
#include "camdyn/cam_spec.hpp"

#include "cam/enum_names.hpp"

namespace camdyn {

using detail::enum_parse;
using detail::enum_to_string;

const char* to_string(CamProfileKind v) { return enum_to_string(detail::kProfileNames, v); }
const char* to_string(FollowerFace v) { return enum_to_string(detail::kFaceNames, v); }
const char* to_string(FollowerMotion v) { return enum_to_string(detail::kMotionNames, v); }

bool parse_enum(std::string_view s, CamProfileKind* out) { return enum_parse(detail::kProfileNames, s, out); }
bool parse_enum(std::string_view s, FollowerFace* out) { return enum_parse(detail::kFaceNames, s, out); }
bool parse_enum(std::string_view s, FollowerMotion* out) { return enum_parse(detail::kMotionNames, s, out); }

}  // namespace camdyn
