// camdyn — how many times a scene's rules were checked in this process (private): the
// one validation function (validate_impl, src/scene/validate.cpp) counts, so a test can show
// that a run validates its scene exactly once.
#pragma once

#include <cstdint>

namespace camdyn::scene_detail {

/// Scenes validated (validate_impl calls) since the process started, over all threads.
std::uint64_t validation_count();

}  // namespace camdyn::scene_detail
