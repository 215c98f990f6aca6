#pragma once
// Shared parts of `pcr fk` and `pcr ik`: model loading, inputs by name, options, result outputs.
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "cli_arguments.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/robot_model.hpp"

namespace pcr_app {

/// Exit codes of the solve commands (and of main for what escapes them: kInternalError).
enum ExitCode { kConverged = 0, kSolveFailed = 1, kBadUsage = 2, kOutputFailed = 3, kInternalError = 4 };

/// Loads MODEL; a missing file is a UsageError naming it (load errors are pcr::InputError).
std::shared_ptr<const pcr::RobotModel> load_model(const std::string& path);

/// The model's default inputs with the --input NAME=VALUE overrides; UsageError for an unknown name
/// (listing the valid ones) or a value outside the input's bounds.
pcr::VecX resolve_inputs(const pcr::RobotModel& model, const std::vector<NamedArgument>& overrides);

pcr::KinematicsOptions kinematics_options(const SolveArguments& args);

/// Table or JSON to out, then the files asked for. Returns kConverged, or kOutputFailed after a
/// message on err when a file could not be written.
int write_outputs(const SolveArguments& args, const pcr::RobotModel& model,
                  const pcr::RobotSolution& solution, const std::vector<pcr::LinkTarget>& targets,
                  const std::string& title, std::ostream& out, std::ostream& err);

/// `pcr fk ...` and `pcr ik ...` (argv[1] is the command); exit codes above.
int fk_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err);
int ik_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace pcr_app
