#pragma once
// IK targets of `pcr ik` and `pcr path --targets`: parsing, component masks (--components), the check
// that they ask for no more rows than the robot has inputs, and the table of target errors.
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "cli_arguments.hpp"
#include "pcr/robots/kinematics.hpp"

namespace pcr_app {

/// A target from --target (3 numbers: position, 7: pose) or --orientation-only (4 numbers).
pcr::LinkTarget parse_target(const NamedArgument& arg);

/// Index 0..5 of a component name x, y, z (world position), rx, ry, rz (rotation about the target
/// frame's axes), or -1.
int component_index(const std::string& name);
/// "x, y, z, rx" of the components a target selects (its mode and its switches).
std::string selected_components(const pcr::LinkTarget& target);
/// How many equations the target adds: its selected components.
int target_rows(const pcr::LinkTarget& target);

/// Applies --components LINK=LIST: the target on LINK meets only the listed components. UsageError for a
/// link without a target, an unknown component or one its mode does not have (rx on a position target).
void apply_components(std::vector<pcr::LinkTarget>& targets, const std::vector<NamedArgument>& components);

/// UsageError when the targets select more rows than the model has inputs, with the counts and the
/// components the inputs move least at `reference` (an FK solve there; no IK solve): those to drop.
void check_target_rows(const std::shared_ptr<const pcr::RobotAssembly>& assembly,
                       const std::vector<pcr::LinkTarget>& targets, const pcr::VecX& reference,
                       const pcr::KinematicsOptions& options);

/// One line per target: how far the reached link pose is from it (mm, degrees).
void print_target_errors(std::ostream& out, const pcr::RobotModel& model, const pcr::RobotSolution& solution,
                         const std::vector<pcr::LinkTarget>& targets);

/// Names of the target links that are not platforms (tool links), then `extra`, without repeats.
std::vector<std::string> reported_links(const pcr::RobotModel& model,
                                        const std::vector<pcr::LinkTarget>& targets,
                                        const std::vector<std::string>& extra);

}  // namespace pcr_app
