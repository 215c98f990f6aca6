#pragma once
// Shared by the paths-through-folds tests: a shipped model's assembly, a state's platform position, a
// snap's landing point.
#include <memory>
#include <string>

#include "pcr/robots/path_through_folds.hpp"
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

/// The accepted continuation point at a snap's landing (its platform where the snap put it), or nullptr.
inline const TracePoint* landing_of(const RobotAssembly& a, const PathThroughFoldsResult& r,
                                    const PathEvent& snap) {
  for (const TracePoint& t : r.trace)
    if ((platform_position(a, t.state) - snap.platforms_after[0].position).norm() < 1e-12) return &t;
  return nullptr;
}

}  // namespace pcr::test
