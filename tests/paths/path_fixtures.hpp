#pragma once
// Shared by the paths-through-folds tests: a shipped model's assembly and a state's platform position.
#include <memory>
#include <string>

#include "pcr/robots/robot_assembly.hpp"
#include "pcr/robots/urdf_loader.hpp"

namespace pcr::test {

inline std::shared_ptr<const RobotAssembly> shipped(const std::string& name) {
  return std::make_shared<const RobotAssembly>(
      std::make_shared<const RobotModel>(load_robot_model(PCR_MODEL_DIR "/" + name + ".urdf")));
}

/// Platform position of state x (the first platform).
inline Vec3 platform_position(const RobotAssembly& a, const VecX& x) {
  return a.platform_pose(x, 0).position;
}

}  // namespace pcr::test
