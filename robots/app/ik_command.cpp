// pcr ik MODEL --target LINK=x,y,z[,qw,qx,qy,qz] [--orientation-only LINK=qw,qx,qy,qz]
// [--components LINK=x,y,z,rx,ry,rz] [options]: inverse kinematics.
#include "solve_command.hpp"
#include "targets.hpp"

namespace pcr_app {

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
  apply_components(targets, args.components);
  const std::vector<std::string> links = reported_links(*model, targets, args.links);
  const pcr::VecX reference = resolve_inputs(*model, args.inputs);
  const pcr::KinematicsOptions options = kinematics_options(args);
  const auto assembly = std::make_shared<const pcr::RobotAssembly>(model, options.assembly);
  check_target_rows(assembly, targets, reference, options);
  pcr::InverseKinematics ik(assembly, targets, options);
  const pcr::RobotSolution solution = ik.solve(poses, &reference);
  pcr::SolutionExtras extras;
  extras.links = pcr::link_poses(*model, solution, links);
  const int written = write_outputs(args, *model, solution, targets, extras, "inverse kinematics", out, err);
  if (!args.json) print_target_errors(out, *model, solution, targets);
  if (!solution.summary.converged()) {
    err << "pcr ik: no solution: the target is unreachable within the input bounds or the solve failed ("
        << solution.summary.brief_report() << ")\n";
    return kSolveFailed;
  }
  return written;
}

}  // namespace pcr_app
