// Uses the installed pcr: loads a model and solves its forward kinematics.
#include <iostream>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  auto model = std::make_shared<const pcr::RobotModel>(pcr::load_robot_model(argv[1]));
  pcr::ForwardKinematics fk(model);
  const pcr::RobotSolution s = fk.solve(model->default_input_values());
  std::cout << s.summary.brief_report() << "\n";
  return s.summary.converged() ? 0 : 1;
}
