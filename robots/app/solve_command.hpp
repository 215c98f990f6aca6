#pragma once
// Shared parts of the solve commands: model loading, inputs by name, options, result outputs.
#include <fstream>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "cli_arguments.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/robot_model.hpp"

namespace pcr_app {

/// Exit codes of the solve commands (and of main for what escapes them: kInternalError).
enum ExitCode { kConverged = 0, kSolveFailed = 1, kBadUsage = 2, kOutputFailed = 3, kInternalError = 4 };

/// Loads MODEL; a missing file is a UsageError naming it (load errors are pcr::InputError).
std::shared_ptr<const pcr::RobotModel> load_model(const std::string& path);
/// load_model(args.model_path), and every --link LINK must name one of its links (pcr::InputError naming
/// an unknown one).
std::shared_ptr<const pcr::RobotModel> load_model_with_links(const SolveArguments& args);

/// The model's default inputs with the --input NAME=VALUE overrides; UsageError for an unknown name
/// (listing the valid ones) or a value outside the input's bounds.
pcr::VecX resolve_inputs(const pcr::RobotModel& model, const std::vector<NamedArgument>& overrides);

pcr::KinematicsOptions kinematics_options(const SolveArguments& args);

/// Whether a JSON output is asked for (--json or --json-file).
bool wants_json(const SolveArguments& args);

/// The poses of `links` and, when `derivatives` and the solve converged, the input Jacobian and the
/// compliance of every platform at fk's last solution (left out, with a note on err, where the Jacobian is
/// singular).
pcr::SolutionExtras solution_extras(const pcr::ForwardKinematics& fk, const pcr::RobotSolution& solution,
                                    const std::vector<std::string>& links, bool derivatives,
                                    std::ostream& err, const std::string& prefix);

/// Table (with the extras' links) or JSON to out, then the files asked for. Returns kConverged, or
/// kOutputFailed after a message on err when a file could not be written.
int write_outputs(const SolveArguments& args, const pcr::RobotModel& model,
                  const pcr::RobotSolution& solution, const std::vector<pcr::LinkTarget>& targets,
                  const pcr::SolutionExtras& extras, const std::string& title, std::ostream& out,
                  std::ostream& err);

/// Creates the parent directories of a file to be written (a failure shows when it is written).
void make_parent_directories(const std::string& file);

/// Opens FILE for writing; throws pcr::InputError naming the option and the file.
std::ofstream open_output(const std::string& option, const std::string& file);
/// Closes it; throws pcr::InputError when the writes failed.
void close_output(std::ofstream& stream, const std::string& option, const std::string& file);

/// `pcr fk|ik|path|workspace ...` (argv[1] is the command); exit codes above.
int fk_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err);
int ik_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err);
int path_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err);
int workspace_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace pcr_app
