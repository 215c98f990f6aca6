// States pushed along the border's unstable mode (pseudo_transient_snap.hpp).
#include "pcr/math/dense_decompositions.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "pseudo_transient_snap.hpp"

namespace pcr::kinematics {

VecX border_unstable_mode(const RobotAssembly& assembly, const VecX& x) {
  const RobotModel& model = assembly.model();
  const int platforms = static_cast<int>(model.platforms().size());
  const BorderStiffness K = robot_border_stiffness(assembly, x);
  if (!K.ok || K.stiffness.rows() != 6 * platforms + static_cast<int>(model.passive_joints().size()) ||
      K.stiffness.rows() == 0)
    return VecX();
  for (int i = 0; i < platforms; ++i)
    if (assembly.problem().variable(assembly.platform_variable(i)).size != 7) return VecX();
  const SymmetricEigen modes = symmetric_eigen(0.5 * (K.stiffness + K.stiffness.transpose()));
  if (!(modes.values[0] < 0.0)) return VecX();
  return modes.vectors.col(0) / modes.vectors.col(0).cwiseAbs().maxCoeff();
}

VecX pushed_along_border_mode(const RobotAssembly& assembly, const VecX& x, const VecX& mode,
                              double amplitude) {
  const RobotModel& model = assembly.model();
  const int platforms = static_cast<int>(model.platforms().size());
  const std::vector<int>& passive = model.passive_joints();
  const Problem& problem = assembly.problem();
  const double L0 = assembly.length_scale();
  const VecX w = amplitude * mode;
  VecX pushed = x;
  for (int i = 0; i < platforms; ++i) {
    const int offset = problem.variable(assembly.platform_variable(i)).offset;
    // [x, Q]: x + L0 dx_hat, and the world-frame rotation dtheta before R(Q).
    pushed.segment<3>(offset) += L0 * w.segment<3>(6 * i);
    const Quat Q = pushed.segment<4>(offset + 3);
    pushed.segment<4>(offset + 3) = quat_multiply(quat_from_rotation_vector(w.segment<3>(6 * i + 3)), Q);
  }
  for (int j = 0; j < static_cast<int>(passive.size()); ++j) {
    const bool prismatic = model.joints()[passive[j]].type == JointType::Prismatic;
    pushed[problem.variable(assembly.passive_joint_variable(j)).offset] +=
        (prismatic ? L0 : 1.0) * w[6 * platforms + j];
  }
  return pushed;
}

}  // namespace pcr::kinematics
