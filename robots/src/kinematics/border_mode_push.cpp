// A state pushed along the border's unstable mode (pseudo_transient_snap.hpp pushed_along_border_mode).
#include "pcr/math/dense_decompositions.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "pseudo_transient_snap.hpp"

namespace pcr::kinematics {

bool pushed_along_border_mode(const RobotAssembly& assembly, const VecX& x, double amplitude, VecX& pushed) {
  const RobotModel& model = assembly.model();
  const int platforms = static_cast<int>(model.platforms().size());
  const std::vector<int>& passive = model.passive_joints();
  const BorderStiffness K = robot_border_stiffness(assembly, x);
  if (!K.ok || K.stiffness.rows() != 6 * platforms + static_cast<int>(passive.size()) ||
      K.stiffness.rows() == 0)
    return false;
  const SymmetricEigen modes = symmetric_eigen(0.5 * (K.stiffness + K.stiffness.transpose()));
  if (!(modes.values[0] < 0.0)) return false;
  const VecX w = modes.vectors.col(0) * (amplitude / modes.vectors.col(0).cwiseAbs().maxCoeff());
  const Problem& problem = assembly.problem();
  const double L0 = assembly.length_scale();
  pushed = x;
  for (int i = 0; i < platforms; ++i) {
    const VariableBlock& block = problem.variable(assembly.platform_variable(i));
    if (block.size != 7) return false;
    // [x, Q]: x + L0 dx_hat, and the world-frame rotation dtheta before R(Q).
    pushed.segment<3>(block.offset) += L0 * w.segment<3>(6 * i);
    const Quat Q = pushed.segment<4>(block.offset + 3);
    pushed.segment<4>(block.offset + 3) =
        quat_multiply(quat_from_rotation_vector(w.segment<3>(6 * i + 3)), Q);
  }
  for (int j = 0; j < static_cast<int>(passive.size()); ++j) {
    const bool prismatic = model.joints()[passive[j]].type == JointType::Prismatic;
    pushed[problem.variable(assembly.passive_joint_variable(j)).offset] +=
        (prismatic ? L0 : 1.0) * w[6 * platforms + j];
  }
  return true;
}

}  // namespace pcr::kinematics
