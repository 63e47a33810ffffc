// camdyn (private) — the coil-clash results of a run (summary.json "coil_clash";
// docs/guide/elements.md "A spring whose coils clash").
#pragma once

#include "camdyn/summary.hpp"

namespace camdyn {
namespace detail {

/// Fills s.coil_clash from the coil contacts' results (s.contacts entries with a
/// coil_spring) and the events: per spring whose coils clash, its coil-to-coil impacts, the
/// coils that closed, the cam angle of the first impact and the largest closing speed.
void collect_coil_clash(Summary& s);

}  // namespace detail
}  // namespace camdyn
