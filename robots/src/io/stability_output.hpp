#pragma once
// The stability verdict in the results (internal header of pcr::robots; docs/results_format.md).
#include <ostream>

#include "pcr/robots/io/json_writer.hpp"
#include "pcr/rods/stability/stability.hpp"

namespace pcr {

/// One table line "stability: ..." (nothing when not checked).
void write_stability_line(std::ostream& out, const Stability& stability);
/// The member "stability": {...} of the results object (nothing when not checked).
void write_stability_member(JsonWriter& json, const Stability& stability);

}  // namespace pcr
