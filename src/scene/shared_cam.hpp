// camdyn (private) — one Cam per cam spec, shared by every part of a run that needs it.
#pragma once

#include <memory>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"  // operator==(CamSpec): the key table's [cam] keys

namespace camdyn {
namespace detail {

/// The cam of `spec`, built once and shared: a run asks for its cam in several places (the
/// scene's checks, the mechanism's builder, the start, the contact run, the verdict), and
/// building one (a law's or an arc chain's geometry, the smallest radius of curvature located
/// between samples) costs more than a short run's integration. The last few distinct specs
/// are kept (compared key by key, operator==); a "table" profile's key also holds the
/// lift-table file's size and modification time, so an edited file is read again.
/// Thread-safe (a Cam's const members may be called concurrently).
/// @throws SceneError as Cam(spec) (a failed build is not kept).
std::shared_ptr<const Cam> shared_cam(const CamSpec& spec);

}  // namespace detail
}  // namespace camdyn
