// pcr ik MODEL --target LINK=x,y,z[,qw,qx,qy,qz] [--orientation-only LINK=qw,qx,qy,qz] [options]:
// inverse kinematics.
#include <cstdio>

#include "pcr/math/so3.hpp"
#include "pcr/robots/io/robot_outline.hpp"
#include "solve_command.hpp"

namespace pcr_app {
namespace {

/// A target from --target (3 numbers: position, 7: pose) or --orientation-only (4 numbers).
pcr::LinkTarget parse_target(const NamedArgument& arg) {
  const std::vector<double> v = parse_numbers(arg.value, arg.text());
  pcr::LinkTarget target;
  target.link = arg.name;
  size_t q = 0;  // index of the quaternion's w, if any
  if (arg.option == "--orientation-only") {
    if (v.size() != 4) throw UsageError(arg.text() + ": expected 4 numbers qw,qx,qy,qz");
    target.mode = pcr::LinkTarget::Mode::Orientation;
  } else if (v.size() == 3) {
    target.mode = pcr::LinkTarget::Mode::Position;
  } else if (v.size() == 7) {
    target.mode = pcr::LinkTarget::Mode::Pose;
    q = 3;
  } else {
    throw UsageError(arg.text() + ": expected 3 numbers x,y,z or 7 numbers x,y,z,qw,qx,qy,qz, got " +
                     std::to_string(v.size()));
  }
  if (target.mode != pcr::LinkTarget::Mode::Orientation) target.pose.position = pcr::Vec3(v[0], v[1], v[2]);
  if (target.mode != pcr::LinkTarget::Mode::Position) {
    const pcr::Quat quaternion(v[q], v[q + 1], v[q + 2], v[q + 3]);
    if (!(quaternion.norm() > 1e-12)) throw UsageError(arg.text() + ": the quaternion is zero");
    target.pose.orientation = quaternion.normalized();
  }
  return target;
}

/// One line per target: how far the reached link pose is from it (mm, degrees).
void print_target_errors(std::ostream& out, const pcr::RobotModel& model, const pcr::RobotSolution& solution,
                         const std::vector<pcr::LinkTarget>& targets) {
  const pcr::VecX q = pcr::joint_values_of_inputs(model, solution.inputs);
  for (const pcr::LinkTarget& target : targets) {
    const pcr::Pose reached = model.link_pose(model.link_index(target.link), q, solution.platforms);
    const double position_error_mm = (reached.position - target.pose.position).norm() * 1e3;
    const double angle_error_deg =
        pcr::rotation_angle_between(reached.rotation(), target.pose.rotation()) * 57.295779513082321;
    char line[200];
    if (target.mode == pcr::LinkTarget::Mode::Position)
      std::snprintf(line, sizeof line, "target %s: position error %.3g mm\n", target.link.c_str(),
                    position_error_mm);
    else if (target.mode == pcr::LinkTarget::Mode::Orientation)
      std::snprintf(line, sizeof line, "target %s: orientation error %.3g deg\n", target.link.c_str(),
                    angle_error_deg);
    else
      std::snprintf(line, sizeof line, "target %s: position error %.3g mm, orientation error %.3g deg\n",
                    target.link.c_str(), position_error_mm, angle_error_deg);
    out << line;
  }
}

}  // namespace

int ik_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  const SolveArguments args = parse_solve_arguments("ik", argc, argv, 2);
  if (args.help) {
    print_solve_usage(out, "ik");
    return kConverged;
  }
  const std::shared_ptr<const pcr::RobotModel> model = load_model(args.model_path);
  std::vector<pcr::LinkTarget> targets;
  std::vector<pcr::Pose> poses;
  for (const NamedArgument& arg : args.targets) {
    targets.push_back(parse_target(arg));
    model->link_index(targets.back().link);  // throws InputError naming an unknown link
    poses.push_back(targets.back().pose);
  }
  const pcr::VecX reference = resolve_inputs(*model, args.inputs);
  pcr::InverseKinematics ik(model, targets, kinematics_options(args));
  const pcr::RobotSolution solution = ik.solve(poses, &reference);
  const int written = write_outputs(args, *model, solution, targets, "inverse kinematics", out, err);
  if (!args.json) print_target_errors(out, *model, solution, targets);
  if (!solution.summary.converged()) {
    err << "pcr ik: no solution: the target is unreachable within the input bounds or the solve failed ("
        << solution.summary.brief_report() << ")\n";
    return kSolveFailed;
  }
  return written;
}

}  // namespace pcr_app
