#include "contact_assembly.hpp"

#include "pcr/core/error.hpp"

namespace pcr::assembly {

void set_contact_discretization(const RodElement& rod, bool use_model_hints, RodDiscretization& d) {
  if (rod.obstacles.empty()) return;
  require(!(use_model_hints && rod.formulation == RodFormulationHint::Primal), "rod '", rod.name,
          "': formulation \"primal\" is not supported with <contact> (contact rows exist in the mixed form "
          "only)");
  d.formulation = RodFormulation::Mixed;
  d.mixed_points = MixedPoints::Midpoints;
  d.contact_forces = true;
}

RodContactOptions rod_contact_options(const RobotModel& model, const RodElement& rod,
                                      ComplementarityFunction function) {
  RodContactOptions options;
  options.radius = rod.contact_radius;
  options.function = function;
  const VecX q0 = model.default_joint_values();
  const std::vector<Pose> platforms = model.initial_platform_poses();
  for (int k : rod.obstacles) {
    require(k >= 0 && k < static_cast<int>(model.obstacles().size()), "rod '", rod.name, "': obstacle index ",
            k, " out of range [0, ", model.obstacles().size(), ")");
    const ObstacleElement& e = model.obstacles()[k];
    if (e.link < 0) {
      options.obstacles.push_back(e.obstacle);
      continue;
    }
    bool moving = model.carrying_platform(e.link) >= 0;
    for (int j = 0; j < static_cast<int>(model.joints().size()); ++j)
      moving = moving || (model.joints()[j].value_index >= 0 && model.joint_moves_link(j, e.link));
    require(!moving, "obstacle '", e.obstacle.name, "' on link '", model.links()[e.link].name,
            "': the link moves (a joint or a platform carries it); contact with moving obstacles is not "
            "supported (their reaction on the link is not modelled)");
    const Pose pose = model.link_pose(e.link, q0, platforms);
    options.obstacles.push_back(e.obstacle.transformed(pose.rotation(), pose.position));
  }
  return options;
}

}  // namespace pcr::assembly
