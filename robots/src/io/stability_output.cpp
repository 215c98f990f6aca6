#include "stability_output.hpp"

#include <cstdio>

namespace pcr {

void write_stability_line(std::ostream& out, const Stability& s) {
  if (s.verdict == StabilityVerdict::NotChecked) return;
  out << "stability: " << to_string(s.verdict);
  if (s.verdict == StabilityVerdict::Unknown) {
    out << " (" << s.reason << ")\n";
    return;
  }
  char margin[96];
  std::snprintf(margin, sizeof margin, ", margin %.4g (x %.3g J, lengths / %.3g m)", s.margin, s.energy_scale,
                s.length_scale);
  out << " (" << s.unstable_modes << " unstable mode" << (s.unstable_modes == 1 ? "" : "s");
  if (s.neutral_modes > 0) out << ", " << s.neutral_modes << " neutral";
  out << margin << ")\n";
  if (!s.reason.empty()) out << "  " << s.reason << "\n";
}

void write_stability_member(JsonWriter& json, const Stability& s) {
  if (s.verdict == StabilityVerdict::NotChecked) return;
  json.key("stability");
  json.begin_object();
  json.member("verdict", to_string(s.verdict));
  if (s.verdict != StabilityVerdict::Unknown) {
    json.member("unstable_modes", s.unstable_modes);
    json.member("neutral_modes", s.neutral_modes);
    json.member("margin", s.margin);
    json.member("length_scale", s.length_scale);
    json.member("energy_scale", s.energy_scale);
    json.member("asymmetry", s.asymmetry);
    json.key("rod_unstable_modes");
    json.begin_array();
    for (int n : s.rod_unstable_modes) json.value(n);
    json.end_array();
    json.member("platform_unstable_modes", s.border_unstable_modes);
  }
  json.member("reason", s.reason);
  json.end_object();
}

}  // namespace pcr
