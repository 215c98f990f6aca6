#pragma once
// The contact set in the results (internal header of pcr::robots; docs/contact.md, docs/results_format.md).
#include <ostream>
#include <vector>

#include "pcr/robots/io/json_writer.hpp"
#include "pcr/rods/rod_contact.hpp"

namespace pcr {

/// The member "contacts": [{rod, obstacle, force, min_gap, min_gap_arc_length, intervals: [{s_begin,
/// s_end, force}]}] of the results object (nothing when no rod has obstacles).
void write_contacts_member(JsonWriter& json, const std::vector<ObstacleContact>& contacts);
/// One table line per rod and obstacle: "contact rod/obstacle: [s0, s1] m force (fx, fy, fz) N ...".
void write_contact_lines(std::ostream& out, const std::vector<ObstacleContact>& contacts);

}  // namespace pcr
