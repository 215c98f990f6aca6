#pragma once
// The options of KinematicsOptions that take a word, by the names the pcr tool (--NAME WORD, with '-'
// for '_': docs/cli.md) and the Python package (NAME="WORD": docs/python.md) share:
//   solver        newton | ipopt
//   formulation   auto (by slenderness, mixed rods solved condensed) | mixed | condensed | primal
//                 (the last three: exactly that formulation for every rod without a model hint)
//   mixed_points  midpoints | greville
//   objective     distance | effort | energy (inverse kinematics)
//   contact_method  semismooth | ipopt (AssemblyOptions::contact_method; ipopt: forward kinematics only)
#include <string>
#include <vector>

#include "pcr/robots/kinematics.hpp"

namespace pcr {

/// The words option `name` takes, in the order above; empty when `name` is none of these options.
std::vector<std::string> kinematics_option_words(const std::string& name);

/// Sets option `name` to `word`. Throws InputError naming the option and the word, with the valid
/// ones, for an option that takes no word or a word it does not take.
void set_kinematics_option(KinematicsOptions& options, const std::string& name, const std::string& word);

}  // namespace pcr
