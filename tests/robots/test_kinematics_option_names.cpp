// The word options shared by the pcr tool and the Python package (pcr/robots/kinematics_option_names.hpp):
// each word sets the documented field, and an unknown option or word is an InputError naming it and the
// valid ones (part of the test_kinematics module).
#include <boost/test/unit_test.hpp>

#include <string>
#include <utility>

#include "pcr/core/error.hpp"
#include "pcr/robots/kinematics_option_names.hpp"

using namespace pcr;

namespace {

// The message of the InputError that setting `name` to `word` throws ("" when none is thrown).
std::string error_of(const std::string& name, const std::string& word) {
  KinematicsOptions options;
  try {
    set_kinematics_option(options, name, word);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(kinematics_option_names)

BOOST_AUTO_TEST_CASE(an_unknown_option_name_is_an_input_error_listing_the_word_options) {
  const std::string message = error_of("tolerence", "1e-8");
  BOOST_CHECK_MESSAGE(contains(message, "tolerence"), message);
  BOOST_CHECK_MESSAGE(contains(message, "solver, formulation, mixed_points or objective"), message);
  BOOST_CHECK(kinematics_option_words("tolerence").empty());
  BOOST_CHECK(kinematics_option_words("elements").empty());  // a number, not a word
}

BOOST_AUTO_TEST_CASE(a_word_an_option_does_not_take_is_an_input_error_listing_its_words) {
  const std::string message = error_of("formulation", "mixd");
  BOOST_CHECK_MESSAGE(contains(message, "option formulation='mixd'"), message);
  BOOST_CHECK_MESSAGE(contains(message, "expected one of auto, mixed, condensed, primal"), message);
  BOOST_CHECK_MESSAGE(contains(error_of("solver", "Newton"), "expected one of newton, ipopt"),
                      "case matters");
}

BOOST_AUTO_TEST_CASE(each_word_sets_its_documented_field) {
  const KinematicsOptions defaults;
  KinematicsOptions o;
  set_kinematics_option(o, "formulation", "auto");  // the defaults: choice by slenderness
  BOOST_CHECK(o.assembly.formulation_by_slenderness == defaults.assembly.formulation_by_slenderness);
  BOOST_CHECK(o.assembly.condense_mixed_rods == defaults.assembly.condense_mixed_rods);
  BOOST_CHECK(o.assembly.discretization.formulation == defaults.assembly.discretization.formulation);
  const std::pair<const char*, RodFormulation> formulations[] = {{"primal", RodFormulation::Primal},
                                                                 {"mixed", RodFormulation::Mixed},
                                                                 {"condensed", RodFormulation::Condensed}};
  for (const auto& [word, formulation] : formulations) {
    KinematicsOptions f;
    set_kinematics_option(f, "formulation", word);
    BOOST_CHECK(f.assembly.discretization.formulation == formulation);
    BOOST_CHECK(!f.assembly.formulation_by_slenderness);  // exactly the formulation asked for
    BOOST_CHECK(!f.assembly.condense_mixed_rods);
  }
  set_kinematics_option(o, "solver", "ipopt");
  BOOST_CHECK(o.solver == SolverKind::Ipopt);
  set_kinematics_option(o, "solver", "newton");
  BOOST_CHECK(o.solver == SolverKind::Newton);
  set_kinematics_option(o, "mixed_points", "greville");
  BOOST_CHECK(o.assembly.discretization.mixed_points == MixedPoints::Greville);
  set_kinematics_option(o, "mixed_points", "midpoints");
  BOOST_CHECK(o.assembly.discretization.mixed_points == MixedPoints::Midpoints);
  set_kinematics_option(o, "objective", "effort");
  BOOST_CHECK(o.ik.objective == IkObjective::ActuationEffort);
  set_kinematics_option(o, "objective", "energy");
  BOOST_CHECK(o.ik.objective == IkObjective::ElasticEnergy);
  set_kinematics_option(o, "objective", "distance");
  BOOST_CHECK(o.ik.objective == IkObjective::InputDistance);
}

BOOST_AUTO_TEST_SUITE_END()
