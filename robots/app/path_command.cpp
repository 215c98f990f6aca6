// pcr path MODEL (--inputs FILE.csv | --targets FILE.csv) [options]: forward or inverse kinematics along
// the rows of a file, one kinematics object warm-started from point to point.
#include <algorithm>
#include <cstdio>
#include <string>

#include "pcr/core/error.hpp"

#include "path_files.hpp"
#include "pcr/robots/io/path_writers.hpp"
#include "pcr/robots/path_through_folds.hpp"
#include "progress_bar.hpp"
#include "solve_command.hpp"
#include "targets.hpp"

namespace pcr_app {
namespace {

std::vector<pcr::PathPoint> fk_path(const SolveArguments& args,
                                    const std::shared_ptr<const pcr::RobotAssembly>& assembly,
                                    const pcr::KinematicsOptions& options, std::ostream& err) {
  const pcr::RobotModel& model = assembly->model();
  const std::vector<pcr::VecX> rows =
      path_inputs(model, read_number_table(args.inputs_file), resolve_inputs(model, args.inputs));
  pcr::ForwardKinematics fk(assembly, options);
  ProgressBar bar(err, "pcr path", static_cast<std::int64_t>(rows.size()), stderr_is_terminal());
  std::vector<pcr::PathPoint> points;
  std::int64_t failed = 0;
  for (const pcr::VecX& u : rows) {
    pcr::PathPoint point;
    point.solution = fk.solve(u);
    point.extras = solution_extras(fk, point.solution, args.links, wants_json(args), err, "pcr path: ");
    failed += point.solution.summary.converged() ? 0 : 1;
    points.push_back(std::move(point));
    bar.update(static_cast<std::int64_t>(points.size()), failed);
  }
  return points;
}

/// --folds: pseudo-arclength continuation between the rows (path_through_folds.hpp); events into `events`.
std::vector<pcr::PathPoint> fold_path(const SolveArguments& args,
                                      const std::shared_ptr<const pcr::RobotAssembly>& assembly,
                                      const pcr::KinematicsOptions& options,
                                      std::vector<pcr::PathEvent>& events) {
  const pcr::RobotModel& model = assembly->model();
  const std::vector<pcr::VecX> rows =
      path_inputs(model, read_number_table(args.inputs_file), resolve_inputs(model, args.inputs));
  pcr::PathThroughFoldsOptions fold_options;
  fold_options.at_fold = args.folds == "snap" ? pcr::FoldPolicy::Snap : pcr::FoldPolicy::Stop;
  pcr::PathThroughFoldsResult result = pcr::solve_path_through_folds(assembly, options, rows, fold_options);
  std::vector<pcr::PathPoint> points;
  for (pcr::RobotSolution& solution : result.points) {
    pcr::PathPoint point;
    point.solution = std::move(solution);
    point.extras.links = pcr::link_poses(model, point.solution, args.links);
    points.push_back(std::move(point));
  }
  events = std::move(result.events);
  return points;
}

std::vector<pcr::PathPoint> ik_path(const SolveArguments& args,
                                    const std::shared_ptr<const pcr::RobotAssembly>& assembly,
                                    const pcr::KinematicsOptions& options, std::ostream& err) {
  const pcr::RobotModel& model = assembly->model();
  TargetPath path = path_targets(model, read_number_table(args.targets_file));
  apply_components(path.targets, args.components);
  const std::vector<std::string> links = reported_links(model, path.targets, args.links);
  const pcr::VecX reference = resolve_inputs(model, args.inputs);
  check_target_rows(assembly, path.targets, reference, options);
  pcr::InverseKinematics ik(assembly, path.targets, options);
  ProgressBar bar(err, "pcr path", static_cast<std::int64_t>(path.poses.size()), stderr_is_terminal());
  std::vector<pcr::PathPoint> points;
  std::int64_t failed = 0;
  for (const std::vector<pcr::Pose>& poses : path.poses) {
    pcr::PathPoint point;
    // The first point stays close to the reference inputs, the next ones to the previous solution.
    point.solution = ik.solve(poses, points.empty() ? &reference : nullptr);
    point.targets = path.targets;
    for (size_t t = 0; t < poses.size(); ++t) point.targets[t].pose = poses[t];
    point.extras.links = pcr::link_poses(model, point.solution, links);
    failed += point.solution.summary.converged() ? 0 : 1;
    points.push_back(std::move(point));
    bar.update(static_cast<std::int64_t>(points.size()), failed);
  }
  return points;
}

/// The verdict in the table: "stable", "unstable (2)" (unstable modes), "critical", "unknown".
std::string verdict_text(const pcr::Stability& v) {
  const bool unstable = v.verdict == pcr::StabilityVerdict::Unstable;
  return std::string(pcr::to_string(v.verdict)) +
         (unstable ? " (" + std::to_string(v.unstable_modes) + ")" : "");
}

/// One line per point: status, iterations, residual, time, platform positions [mm], and with --stability
/// the verdict.
void write_path_table(std::ostream& out, const pcr::RobotModel& model,
                      const std::vector<pcr::PathPoint>& points, const std::vector<pcr::PathEvent>* events) {
  const bool verdicts = pcr::has_stability_verdicts(points);
  out << "point  status          iterations  residual   time [ms]";
  for (const pcr::Platform& platform : model.platforms()) out << "  " << platform.name << " x, y, z [mm]";
  out << (verdicts ? "  stability" : "") << "\n";
  double seconds = 0.0;
  int iterations = 0, failed = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    const pcr::SolveSummary& s = points[k].solution.summary;
    char line[160];
    std::snprintf(line, sizeof line, "%5zu  %-14s  %10d  %9.2e  %9.3f", k, pcr::to_string(s.status),
                  s.iterations, s.residual_max_abs, s.wall_time_seconds * 1e3);
    out << line;
    for (const pcr::Pose& pose : points[k].solution.platforms) {
      std::snprintf(line, sizeof line, "  %9.3f %9.3f %9.3f", pose.position[0] * 1e3, pose.position[1] * 1e3,
                    pose.position[2] * 1e3);
      out << line;
    }
    if (verdicts) out << "  " << verdict_text(points[k].solution.stability_verdict);
    out << "\n";
    seconds += s.wall_time_seconds;
    iterations += s.iterations;
    failed += s.converged() ? 0 : 1;
  }
  char total[64];
  std::snprintf(total, sizeof total, "%.3g s", seconds);
  out << "model " << model.name() << ": " << points.size() << " points, " << points.size() - failed
      << " converged, " << failed << " failed; " << iterations << " iterations in " << total << "\n";
  if (!events) return;
  for (const pcr::PathEvent& e : *events) out << pcr::to_string(e.kind) << ": " << e.description << "\n";
  out << (events->empty() ? "no fold, snap or bifurcation along the path\n" : "");
}

/// events: those of a path through folds (--folds), else null.
int write_path_outputs(const SolveArguments& args, const pcr::RobotModel& model,
                       const std::vector<pcr::PathPoint>& points, const std::vector<pcr::PathEvent>* events,
                       std::ostream& out, std::ostream& err) {
  try {
    if (args.json) {
      const int non_finite = pcr::write_path_json(out, model, points, events);
      if (non_finite > 0) err << "pcr path: " << non_finite << " non-finite values written as null\n";
    } else {
      write_path_table(out, model, points, events);
    }
    if (!args.json_file.empty()) {
      std::ofstream file = open_output("--json-file", args.json_file);
      pcr::write_path_json(file, model, points, events);
      close_output(file, "--json-file", args.json_file);
    }
    if (!args.csv.empty()) {
      std::ofstream file = open_output("--csv", args.csv);
      if (events)
        pcr::write_path_csv(file, model, points, *events);
      else
        pcr::write_path_csv(file, model, points);
      close_output(file, "--csv", args.csv);
    }
  } catch (const pcr::InputError& e) {
    err << "pcr path: " << e.what() << "\n";
    return kOutputFailed;
  }
  return kConverged;
}

}  // namespace

int path_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  const SolveArguments args = parse_solve_arguments("path", argc, argv, 2);
  if (args.help) {
    print_solve_usage(out, "path");
    return kConverged;
  }
  const std::shared_ptr<const pcr::RobotModel> model = load_model_with_links(args);
  const pcr::KinematicsOptions options = kinematics_options(args);
  const auto assembly = std::make_shared<const pcr::RobotAssembly>(model, options.assembly);
  std::vector<pcr::PathEvent> events;
  const std::vector<pcr::PathPoint> points = !args.folds.empty() ? fold_path(args, assembly, options, events)
                                             : args.inputs_file.empty()
                                                 ? ik_path(args, assembly, options, err)
                                                 : fk_path(args, assembly, options, err);
  const int written =
      write_path_outputs(args, *model, points, args.folds.empty() ? nullptr : &events, out, err);
  size_t failed = 0, first_failed = points.size();
  for (size_t k = 0; k < points.size(); ++k)
    if (!points[k].solution.summary.converged()) {
      ++failed;
      first_failed = std::min(first_failed, k);
    }
  if (failed > 0) {
    err << "pcr path: " << failed << " of " << points.size() << " points failed (the first, point "
        << first_failed << ": " << points[first_failed].solution.summary.brief_report() << ")\n";
    return kSolveFailed;
  }
  return written;
}

}  // namespace pcr_app
