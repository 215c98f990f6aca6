// pcr fk MODEL [--input NAME=VALUE ...] [options]: forward kinematics.
#include "solve_command.hpp"

namespace pcr_app {

int fk_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  const SolveArguments args = parse_solve_arguments("fk", argc, argv, 2);
  if (args.help) {
    print_solve_usage(out, "fk");
    return kConverged;
  }
  const std::shared_ptr<const pcr::RobotModel> model = load_model(args.model_path);
  const pcr::VecX inputs = resolve_inputs(*model, args.inputs);
  pcr::ForwardKinematics fk(model, kinematics_options(args));
  const pcr::RobotSolution solution = fk.solve(inputs);
  const int written = write_outputs(args, *model, solution, {}, "forward kinematics", out, err);
  if (!solution.summary.converged()) {
    err << "pcr fk: the solve failed: " << solution.summary.brief_report() << "\n";
    return kSolveFailed;
  }
  return written;
}

}  // namespace pcr_app
