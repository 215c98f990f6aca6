#include "contact_output.hpp"

namespace pcr {

namespace {

void write_gaps_member(JsonWriter& json, const std::vector<RodContactGap>& gaps) {
  json.key("contact_gaps");
  json.begin_array();
  for (const RodContactGap& g : gaps) {
    json.begin_object();
    json.member("rod", g.rod);
    json.member("obstacle", g.obstacle);
    json.member("min_gap", g.min_gap);
    json.member("arc_length", g.arc_length);
    json.member("tolerance", g.tolerance);
    json.member("penetrates", g.penetrates());
    json.end_object();
  }
  json.end_array();
}

}  // namespace

void write_contacts_member(JsonWriter& json, const std::vector<ObstacleContact>& contacts,
                           const std::vector<RodContactGap>& gaps) {
  if (contacts.empty()) return;
  json.key("contacts");
  json.begin_array();
  for (const ObstacleContact& c : contacts) {
    json.begin_object();
    json.member("rod", c.rod);
    json.member("obstacle", c.obstacle);
    json.key("force");
    json.array(c.force);
    json.member("min_gap", c.min_gap);
    json.member("min_gap_arc_length", c.min_gap_arc_length);
    json.member("concentrated", c.concentrated);
    if (c.adhesive) {
      json.member("tangential_force", c.tangential_force);
    }
    json.key("intervals");
    json.begin_array();
    for (const ContactInterval& interval : c.intervals) {
      json.begin_object();
      json.member("s_begin", interval.s_begin);
      json.member("s_end", interval.s_end);
      json.key("force");
      json.array(interval.force);
      json.member("centroid", interval.centroid);
      json.end_object();
    }
    json.end_array();
    json.end_object();
  }
  json.end_array();
  write_gaps_member(json, gaps);
}

void write_contact_lines(std::ostream& out, const std::vector<ObstacleContact>& contacts,
                         const std::vector<RodContactGap>& gaps) {
  for (const ObstacleContact& c : contacts) {
    out << "contact " << c.rod << " / " << c.obstacle << ":";
    if (c.intervals.empty()) out << " none";
    for (const ContactInterval& i : c.intervals) {
      if (c.concentrated) {
        out << " point at s = " << i.centroid << " m force (" << i.force.transpose() << ") N;";
      } else {
        out << " [" << i.s_begin << ", " << i.s_end << "] m force (" << i.force.transpose()
            << ") N centroid s = " << i.centroid << " m;";
      }
    }
    if (c.adhesive) out << " tangential force " << c.tangential_force << " N (adhesion);";
    out << " min gap " << c.min_gap << " m at s = " << c.min_gap_arc_length << " m\n";
  }
  for (const RodContactGap& g : gaps) {
    out << "contact gap " << g.rod << ": min " << g.min_gap << " m at s = " << g.arc_length << " m ("
        << g.obstacle << "), tolerated penetration " << g.tolerance << " m\n";
    if (g.penetrates()) out << "warning: " << contact_penetration_warning({g}) << "\n";
  }
}

}  // namespace pcr
