#pragma once
// Writers of a path: solutions at consecutive points (`pcr path`, forward kinematics along input rows or
// inverse kinematics along target rows). SI units, world frame; formats in docs/results_format.md.
#include <ostream>
#include <vector>

#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/robots/path_through_folds.hpp"

namespace pcr {

struct PathPoint {
  RobotSolution solution;
  std::vector<LinkTarget> targets;  ///< this point's targets (a path of targets); empty along inputs
  SolutionExtras extras;
};

/// Whether any point carries a stability verdict (the verdict was asked for).
bool has_stability_verdicts(const std::vector<PathPoint>& points);

/// CSV, one row per point: point (from 0), the inputs by name, NAME.x, .y, .z, .qw, .qx, .qy, .qz per
/// platform and per link of the first point's extras.links, LINK.position_error and
/// LINK.orientation_error per target of the first point, then status, iterations, residual_max_abs,
/// wall_time_seconds and message (quoted), and where has_stability_verdicts: stability, unstable_modes,
/// stability_margin, stability_reason (quoted). Non-finite numbers are empty fields.
void write_path_csv(std::ostream& out, const RobotModel& model, const std::vector<PathPoint>& points);
/// The same with the events of a path through folds as rows of their own, in path order before the
/// point they lead to: point = fold, snap or bifurcation, the inputs and platform poses at the event
/// (a snap: where it lands), status = the kind, message = its description (docs/results_format.md).
void write_path_csv(std::ostream& out, const RobotModel& model, const std::vector<PathPoint>& points,
                    const std::vector<PathEvent>& events);

/// JSON object {model, command: "path", points, failures, results: [one write_solution_object per
/// point], non_finite_values}; returns how many numbers were not finite (written as null).
int write_path_json(std::ostream& out, const RobotModel& model, const std::vector<PathPoint>& points);
/// The same with "events": [one object per event of a path through folds] when events is given.
int write_path_json(std::ostream& out, const RobotModel& model, const std::vector<PathPoint>& points,
                    const std::vector<PathEvent>* events);

}  // namespace pcr
