// camdyn (private) — enumerations as tables of their spellings: EnumName, the lookups both
// ways, and the cam's enumerations (the scene's own tables are in scene/detail.hpp, the key
// table lists a key's allowed spellings from them).
#pragma once

#include <cstddef>
#include <string_view>

#include "camdyn/cam_spec.hpp"

namespace camdyn {
namespace detail {

template <class E>
struct EnumName {
  E value;
  const char* name;
};

template <class E, std::size_t N>
const char* enum_to_string(const EnumName<E> (&names)[N], E v) {
  for (const auto& n : names)
    if (n.value == v) return n.name;
  return "?";
}

template <class E, std::size_t N>
bool enum_parse(const EnumName<E> (&names)[N], std::string_view s, E* out) {
  for (const auto& n : names)
    if (s == n.name) {
      if (out) *out = n.value;
      return true;
    }
  return false;
}

inline constexpr EnumName<CamProfileKind> kProfileNames[] = {
    {CamProfileKind::Points, "points"}, {CamProfileKind::Lift, "lift"}, {CamProfileKind::Circle, "circle"},
    {CamProfileKind::Law, "law"}, {CamProfileKind::Arc, "arc"}, {CamProfileKind::Arcs, "arcs"}, {CamProfileKind::Table, "table"}};
inline constexpr EnumName<FollowerFace> kFaceNames[] = {{FollowerFace::Flat, "flat"},
                                                        {FollowerFace::KnifeEdge, "knife_edge"},
                                                        {FollowerFace::Roller, "roller"},
                                                        {FollowerFace::Point, "point"}};
inline constexpr EnumName<FollowerMotion> kMotionNames[] = {{FollowerMotion::Translating, "translating"},
                                                            {FollowerMotion::Oscillating, "oscillating"}};

}  // namespace detail
}  // namespace camdyn
