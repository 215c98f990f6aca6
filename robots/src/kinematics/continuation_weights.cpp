// continuation_weights (continuation_weights.hpp).
#include "continuation_weights.hpp"

namespace pcr::kinematics {

ContinuationWeights continuation_weights(const RobotAssembly& assembly) {
  const Problem& problem = assembly.problem();
  const RobotModel& model = assembly.model();
  const double inverse_length = 1.0 / assembly.length_scale();
  ContinuationWeights w = ContinuationWeights::Zero(problem.num_variables());
  for (int i = 0; i < assembly.num_rods(); ++i) {
    const CollocationRod& rod = assembly.rod(i);
    const collocation::PointLayout& layout = rod.point_layout();
    const int size = rod.control_point_size();
    for (int j = 0; j < rod.num_control_points(); ++j) {
      const int o = assembly.rod_variables(i).control_point_offset + j * size;
      w.segment<3>(o + layout.p).setConstant(inverse_length);
      w.segment<4>(o + layout.q).setOnes();
    }
  }
  for (size_t p = 0; p < model.platforms().size(); ++p) {
    const int o = problem.variable(assembly.platform_variable(static_cast<int>(p))).offset;  // [x (3), Q (4)]
    w.segment<3>(o).setConstant(inverse_length);
    w.segment<4>(o + 3).setOnes();
  }
  for (size_t j = 0; j < model.passive_joints().size(); ++j) {
    const bool prismatic = model.joints()[model.passive_joints()[j]].type == JointType::Prismatic;
    w[problem.variable(assembly.passive_joint_variable(static_cast<int>(j))).offset] =
        prismatic ? inverse_length : 1.0;
  }
  return w;
}

}  // namespace pcr::kinematics
