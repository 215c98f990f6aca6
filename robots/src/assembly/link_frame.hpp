#pragma once
// Where a frame attached to a link sits in the world, as a function of the assembly's unknowns
// (internal header of pcr::robots). The attachment frame is  z = [x (3), Q (4)]  composed with a
// constant offset (r, q_off):  p = x + R(Q) r,  R = R(Q) R(q_off). The pair z is
//  - Constant: a world pose (links fixed to the base, no moving joint on the way);
//  - Platform: the platform's pose variable block (links rigidly carried by a platform);
//  - Joints:   the link's world pose from URDF forward kinematics of the moving joints on its path,
//              with dz/dtheta from the joint axes (prismatic: dx = w; revolute: dx = w x (x - o),
//              dQ = 1/2 [0, w] (x) Q, w the joint axis and o the joint origin in the world).
#include <vector>

#include "pcr/robots/robot_model.hpp"
#include "pcr/solve/residual_block.hpp"

namespace pcr::assembly {

using Vec7 = Eigen::Matrix<double, 7, 1>;

struct LinkFrame {
  enum class Kind { Constant, Platform, Joints };
  Kind kind = Kind::Constant;
  Pose offset;  ///< attachment in the frame z describes
  Vec7 constant = Vec7::Zero();  ///< z of a Constant frame
  std::vector<VariableId> variables;  ///< the platform block, or one block per moving joint on the path
  std::vector<int> joints;            ///< model joint indices matching variables (Joints kind)
  const RobotModel* model = nullptr;
  int link = -1;

  /// The frame of `attachment` on its link, for the given assembly variables.
  static LinkFrame of(const RobotModel& model, int link, const Pose& attachment,
                      const std::vector<VariableId>& platform_variables, const std::vector<VariableId>& joint_variables);

  /// z and, when dz is given, dz/d(variables()[k]) as 7 x size columns stacked (7 x total size).
  void evaluate(const double* const* values, Vec7& z, MatX* dz) const;
  /// World pose of the attachment for z.
  Pose attachment_pose(const Vec7& z) const;
};

}  // namespace pcr::assembly
