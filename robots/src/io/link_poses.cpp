// Reached poses of named links in a solution (tool links carried by platforms, links of the base tree).
#include "pcr/core/error.hpp"
#include "pcr/robots/io/robot_outline.hpp"
#include "pcr/robots/io/solution_writers.hpp"

namespace pcr {

VecX joint_values_of_solution(const RobotModel& model, const RobotSolution& solution) {
  VecX q = joint_values_of_inputs(model, solution.inputs);
  const std::vector<int>& passive = model.passive_joints();
  if (solution.passive_joints.size() == static_cast<int>(passive.size()))
    for (size_t k = 0; k < passive.size(); ++k)
      q[model.joints()[passive[k]].value_index] = solution.passive_joints[static_cast<int>(k)];
  return q;
}

std::vector<LinkPose> link_poses(const RobotModel& model, const RobotSolution& solution,
                                 const std::vector<std::string>& links) {
  std::vector<LinkPose> out;
  if (links.empty()) return out;
  require(solution.platforms.size() == model.platforms().size(), "link_poses: ", solution.platforms.size(),
          " platform poses for ", model.platforms().size(), " platforms");
  const VecX q = joint_values_of_solution(model, solution);
  for (const std::string& link : links)
    out.push_back({link, model.link_pose(model.link_index(link), q, solution.platforms)});
  return out;
}

}  // namespace pcr
