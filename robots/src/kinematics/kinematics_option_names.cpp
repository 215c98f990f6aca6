#include "pcr/robots/kinematics_option_names.hpp"

#include "pcr/core/error.hpp"

namespace pcr {
namespace {

const char* const kWordOptions = "contact_method, solver, formulation, mixed_points or objective";

std::string listed(const std::vector<std::string>& words) {
  std::string list;
  for (const std::string& w : words) list += (list.empty() ? "" : ", ") + w;
  return list;
}

// formulation: "auto" keeps the choice by slenderness (mixed rods solved condensed); the others are
// exactly that formulation for every rod without a model hint.
void set_formulation(KinematicsOptions& o, const std::string& word) {
  if (word == "auto") return;
  o.assembly.discretization.formulation = word == "primal"  ? RodFormulation::Primal
                                          : word == "mixed" ? RodFormulation::Mixed
                                                            : RodFormulation::Condensed;
  o.assembly.formulation_by_slenderness = false;
  o.assembly.condense_mixed_rods = false;
}

}  // namespace

std::vector<std::string> kinematics_option_words(const std::string& name) {
  if (name == "solver") return {"newton", "ipopt"};
  if (name == "formulation") return {"auto", "mixed", "condensed", "primal"};
  if (name == "mixed_points") return {"midpoints", "greville"};
  if (name == "objective") return {"distance", "effort", "energy"};
  if (name == "contact_method") return {"semismooth", "ipopt"};
  return {};
}

void set_kinematics_option(KinematicsOptions& o, const std::string& name, const std::string& word) {
  const std::vector<std::string> words = kinematics_option_words(name);
  require(!words.empty(), "option ", name, "='", word, "': not an option that takes a word (", kWordOptions,
          ")");
  bool known = false;
  for (const std::string& w : words) known = known || w == word;
  require(known, "option ", name, "='", word, "': expected one of ", listed(words));
  if (name == "solver") {
    o.solver = word == "ipopt" ? SolverKind::Ipopt : SolverKind::Newton;
  } else if (name == "formulation") {
    set_formulation(o, word);
  } else if (name == "contact_method") {
    o.assembly.contact_method = word == "ipopt" ? ContactMethod::Ipopt : ContactMethod::Semismooth;
  } else if (name == "mixed_points") {
    o.assembly.discretization.mixed_points =
        word == "greville" ? MixedPoints::Greville : MixedPoints::Midpoints;
  } else {
    o.ik.objective = word == "effort"   ? IkObjective::ActuationEffort
                     : word == "energy" ? IkObjective::ElasticEnergy
                                        : IkObjective::InputDistance;
  }
}

}  // namespace pcr
