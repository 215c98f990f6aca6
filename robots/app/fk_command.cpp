// pcr fk MODEL [--input NAME=VALUE ...] [--link NAME ...] [options]: forward kinematics.
#include "solve_command.hpp"

namespace pcr_app {

int fk_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  const SolveArguments args = parse_solve_arguments("fk", argc, argv, 2);
  if (args.help) {
    print_solve_usage(out, "fk");
    return kConverged;
  }
  const std::shared_ptr<const pcr::RobotModel> model = load_model_with_links(args);
  const pcr::VecX inputs = resolve_inputs(*model, args.inputs);
  pcr::ForwardKinematics fk(model, kinematics_options(args));
  const pcr::RobotSolution solution = fk.solve(inputs);
  const pcr::SolutionExtras extras =
      solution_extras(fk, solution, args.links, wants_json(args), err, "pcr fk: ");
  const int written = write_outputs(args, *model, solution, {}, extras, "forward kinematics", out, err);
  if (!solution.summary.converged()) {
    err << "pcr fk: the solve failed: " << solution.summary.brief_report() << "\n";
    return kSolveFailed;
  }
  return written;
}

}  // namespace pcr_app
