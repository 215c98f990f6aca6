#include "contact_assembly.hpp"

#include <algorithm>

#include "moving_obstacle_block.hpp"
#include "pcr/core/error.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr::assembly {
namespace {

/// Where the obstacle's link moves with: -2 fixed to the world, -1 joints with values (inputs or joints
/// held at their defaults), else the index of the platform that carries it. Throws for a link moved by a
/// passive joint (the reaction is not in the joint's balance).
int obstacle_mover(const RobotModel& model, const ObstacleElement& e) {
  if (e.link < 0) return -2;
  const std::string& link = model.links()[e.link].name;
  require(!model.moved_by_passive_joint(e.link), "obstacle '", e.obstacle.name, "' on link '", link,
          "': the link moves (a passive joint moves it); contact with such obstacles is not supported (the "
          "reaction is not in the passive joint's balance)");
  const int platform = model.carrying_platform(e.link);
  if (platform >= 0) return platform;
  bool moving = false;
  for (int j = 0; j < static_cast<int>(model.joints().size()); ++j)
    moving = moving || (model.joints()[j].value_index >= 0 && model.joint_moves_link(j, e.link));
  return moving ? -1 : -2;
}

/// A rod touching obstacles on a platform: distributed contact only.
void check_platform_contact(const ObstacleElement& e, const RobotModel& model) {
  const std::string& link = model.links()[e.link].name;
  require(
      !concentrated_contact(e.obstacle), "obstacle '", e.obstacle.name, "' on link '", link,
      "': the link moves (a platform carries it); concentrated contact (sharp obstacles, contact=\"point\") "
      "with obstacles on a platform is not supported (use a distributed obstacle)");
}

/// The roles of a contact block's variables (rod_contact.hpp): the control points, then for a midpoint
/// block F_j, the multipliers (when there are distributed obstacles) and the sharp blocks; for a sharp
/// block its [u_c, lambda, G].
std::vector<ContactVariableRole> contact_roles(const ResidualBlock& block, int distributed, int sharp) {
  const int n = static_cast<int>(block.variables().size());
  std::vector<ContactVariableRole> roles(n, ContactVariableRole::ControlPoint);
  if (block.kind() == "rod.sharp_contact") {
    roles[n - 1] = ContactVariableRole::Sharp;
    return roles;
  }
  require(block.kind() == "rod.contact", "moving obstacles: unexpected contact block kind '", block.kind(),
          "'");
  const int points = n - 1 - (distributed > 0 ? 1 : 0) - sharp;
  roles[points] = ContactVariableRole::Vector;
  if (distributed > 0) roles[points + 1] = ContactVariableRole::Plain;
  for (int k = n - sharp; k < n; ++k) roles[k] = ContactVariableRole::Sharp;
  return roles;
}

}  // namespace

void set_contact_discretization(const RodElement& rod, bool use_model_hints, RodDiscretization& d) {
  if (rod.obstacles.empty()) return;
  require(!(use_model_hints && rod.formulation == RodFormulationHint::Primal), "rod '", rod.name,
          "': formulation \"primal\" is not supported with <contact> (contact rows exist in the mixed form "
          "only)");
  d.formulation = RodFormulation::Mixed;
  d.mixed_points = MixedPoints::Midpoints;
  d.contact_forces = true;
}

std::vector<Obstacle> rod_obstacles_at(const RobotModel& model, const RodElement& rod,
                                       const VecX& joint_values, const std::vector<Pose>& platform_poses) {
  std::vector<Obstacle> out;
  for (int k : rod.obstacles) {
    require(k >= 0 && k < static_cast<int>(model.obstacles().size()), "rod '", rod.name, "': obstacle index ",
            k, " out of range [0, ", model.obstacles().size(), ")");
    const ObstacleElement& e = model.obstacles()[k];
    if (e.link < 0) {
      out.push_back(e.obstacle);
      continue;
    }
    const Pose pose = model.link_pose(e.link, joint_values, platform_poses);
    out.push_back(e.obstacle.transformed(pose.rotation(), pose.position));
  }
  return out;
}

RodContactSetup rod_contact_setup(const RobotModel& model, const RodElement& rod,
                                  ComplementarityFunction function, int p_offset,
                                  const std::vector<VariableId>& platform_variables,
                                  const std::vector<VariableId>& joint_variables) {
  RodContactSetup setup;
  RodContactOptions& options = setup.options;
  options.radius = rod.contact_radius;
  options.function = function;
  const VecX q0 = model.default_joint_values();
  const std::vector<Pose> platforms = model.initial_platform_poses();
  options.obstacles = rod_obstacles_at(model, rod, q0, platforms);
  int moving_link = -1, distributed = 0, sharp = 0;
  for (int k : rod.obstacles) {
    const ObstacleElement& e = model.obstacles()[k];
    (concentrated_contact(e.obstacle) ? sharp : distributed) += 1;
    const int mover = obstacle_mover(model, e);
    if (mover == -2) continue;
    if (mover >= 0) check_platform_contact(e, model);
    require(moving_link < 0 || moving_link == e.link, "rod '", rod.name,
            "': its obstacles on moving links are on ", "links '",
            model.links()[std::max(moving_link, 0)].name, "' and '", model.links()[e.link].name,
            "'; a rod may touch obstacles of one moving link only");
    moving_link = e.link;
    setup.platform = mover;
  }
  if (moving_link < 0) return setup;
  for (int k : rod.obstacles)
    require(model.obstacles()[k].link == moving_link, "rod '", rod.name, "': obstacle '",
            model.obstacles()[k].obstacle.name, "' does not move with link '",
            model.links()[moving_link].name,
            "' as the rod's other obstacles do; a rod touching an obstacle on a moving link may touch only "
            "obstacles of that link");
  const LinkFrame frame =
      LinkFrame::of(model, moving_link, Pose::identity(), platform_variables, joint_variables);
  // z0: the frame's value in the initial configuration (the platform's pose, or the link's).
  const Pose initial =
      setup.platform >= 0 ? platforms[setup.platform] : model.link_pose(moving_link, q0, platforms);
  Vec7 z0;
  z0 << initial.position, initial.orientation;
  setup.wrap_block = [frame, z0, p_offset, distributed, sharp](std::shared_ptr<ResidualBlock> block) {
    std::vector<ContactVariableRole> roles = contact_roles(*block, distributed, sharp);
    return make_moving_obstacle_block(std::move(block), std::move(roles), p_offset, frame, z0);
  };
  return setup;
}

PlatformContact platform_contact(const CollocationRod& rod, const RodVariables& vars,
                                 const RodContactVariables& contact) {
  PlatformContact out;
  out.p_offset = rod.point_layout().p;
  out.point_size = rod.control_point_size();
  const std::vector<double> tau = rod.knots().greville();
  for (size_t j = 0; j < contact.midpoints.size(); ++j) {
    PlatformContactCell cell;
    const BasisDerivatives b = basis_derivatives(rod.knots(), contact.midpoints[j], 0);
    for (int i = 0; i < b.values.cols(); ++i) {
      cell.points.push_back(vars.control_points[b.first + i]);
      cell.basis.push_back(b.values(0, i));
    }
    cell.force = vars.contact_forces[j];
    cell.length = vars.length;
    cell.fraction = tau[j + 1] - tau[j];
    out.cells.push_back(std::move(cell));
  }
  return out;
}

}  // namespace pcr::assembly
