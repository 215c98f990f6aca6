#pragma once
// The contact set in the results (internal header of pcr::robots; docs/contact.md, docs/results_format.md).
#include <ostream>
#include <vector>

#include "pcr/robots/io/json_writer.hpp"
#include "pcr/rods/rod_contact.hpp"

namespace pcr {

/// The members "contacts": [{rod, obstacle, force, min_gap, min_gap_arc_length, concentrated,
/// (adhesive rollers) tangential_force, intervals: [{s_begin, s_end, force, centroid}]}] and "contact_gaps":
/// [{rod, obstacle, min_gap, arc_length, tolerance, penetrates}] of the results object (nothing when no rod
/// has obstacles).
void write_contacts_member(JsonWriter& json, const std::vector<ObstacleContact>& contacts,
                           const std::vector<RodContactGap>& gaps);
/// One table line per rod and obstacle: "contact rod/obstacle: [s0, s1] m force (fx, fy, fz) N ...", one
/// per rod with its smallest gap, and a "warning:" line per rod that penetrates beyond its tolerance.
void write_contact_lines(std::ostream& out, const std::vector<ObstacleContact>& contacts,
                         const std::vector<RodContactGap>& gaps);

}  // namespace pcr
