// The robot's total potential energy as a Problem, and its map to the collocation state
// (energy_model.hpp).
#include "energy_model.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include <Eigen/LU>

#include "../assembly/contact_assembly.hpp"
#include "energy_kinematics.hpp"
#include "energy_terms.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr::kinematics {

namespace {

/// A rod end's applied moment: a dead couple on an end that can turn is not conservative.
bool applies_moment(const RodEnd& end) {
  return end.moment.squaredNorm() > 0.0;
}

/// The joint-value vector at the inputs and passive joint values the collocation state x holds.
VecX joint_values_of(const RobotAssembly& assembly, const VecX& x) {
  const RobotModel& m = assembly.model();
  VecX q = m.default_joint_values();
  const VecX u = assembly.inputs(x);
  for (std::size_t i = 0; i < m.inputs().size(); ++i)
    if (m.inputs()[i].kind == ActuationInput::Kind::JointValue)
      q[m.joints()[m.inputs()[i].index].value_index] = u[i];
  for (std::size_t j = 0; j < m.passive_joints().size(); ++j)
    q[m.joints()[m.passive_joints()[j]].value_index] =
        x[assembly.problem().variable(assembly.passive_joint_variable(static_cast<int>(j))).offset];
  return q;
}

/// Why the obstacle's contact is not among the energy's gap rows, or "".
std::string contact_refusal(const RobotModel& model, const RodElement& rod, const ObstacleElement& e) {
  const std::string which = "rod '" + rod.name + "' and obstacle '" + e.obstacle.name + "': ";
  if (concentrated_contact(e.obstacle))
    return which +
           "a contact at one section (sharp obstacle, point contact or adhesion) is not part of the "
           "energy";
  if (e.link >= 0 && model.carrying_platform(e.link) >= 0)
    return which + "an obstacle on a platform is not part of the energy";
  return "";
}

}  // namespace

std::string energy_model_refusal(const RobotModel& model) {
  for (const RodElement& r : model.rods()) {
    const RodModel& rod = r.rod;
    for (int k : r.obstacles) {
      const std::string refusal = contact_refusal(model, r, model.obstacles()[k]);
      if (!refusal.empty()) return refusal;
    }
    if (rod.drawing_speed != 0.0)
      return "rod '" + r.name + "' is drawn (a steady motion, not an equilibrium)";
    if (rod.loads.moment_per_length.squaredNorm() > 0.0)
      return "rod '" + r.name + "' carries a distributed couple (not conservative)";
    if (applies_moment(rod.base) || applies_moment(rod.tip))
      return "rod '" + r.name + "' has a moment applied at an end (not conservative)";
  }
  for (const ExternalLoad& load : model.loads())
    if (load.torque.squaredNorm() > 0.0)
      return "a dead torque on link '" + model.links()[load.link].name + "' (not conservative)";
  for (int j : model.passive_joints())
    for (std::size_t l = 0; l < model.links().size(); ++l)
      if (model.carrying_platform(static_cast<int>(l)) >= 0 && model.joint_moves_link(j, static_cast<int>(l)))
        return "passive joint '" + model.joints()[j].name + "' is below a platform";
  return "";
}

EnergyModel::EnergyModel(const RobotAssembly& assembly, const VecX& x)
    : assembly_(assembly), energy_scale_(assembly.moment_scale() * assembly.length_scale()) {
  LinkState links{joint_values_of(assembly, x), {}};
  for (std::size_t p = 0; p < assembly.model().platforms().size(); ++p)
    links.platform_poses.push_back(assembly.platform_pose(x, static_cast<int>(p)));
  add_rods(x);
  add_platforms_and_passive_joints(links);
  add_couplings(links);
  add_obstacle_gaps(links);
  find_shared_slices();
}

void EnergyModel::add_rods(const VecX& x) {
  for (int i = 0; i < assembly_.num_rods(); ++i) {
    const CollocationRod& rod = assembly_.rod(i);
    std::vector<VariableId> points;
    for (int k = 0; k < rod.num_control_points(); ++k) {
      points.push_back(
          problem_.add_variable_block(rod.model().name + "." + std::to_string(k), VecX::Zero(7)));
      problem_.add_residual_block(std::make_shared<UnitQuaternionRow>(points.back()));
    }
    problem_.add_objective_term(std::make_shared<RodEnergyTerm>(
        rod, rod.length(x, assembly_.rod_variables(i)), points, energy_scale_));
    rod_points_.push_back(points);
  }
}

void EnergyModel::add_platforms_and_passive_joints(const LinkState& links) {
  const RobotModel& m = assembly_.model();
  const VecX& q = links.joint_values;
  const std::vector<Pose>& poses = links.platform_poses;
  for (std::size_t p = 0; p < m.platforms().size(); ++p) {
    const Platform& platform = m.platforms()[p];
    platforms_.push_back(problem_.add_variable_block("platform." + platform.name, VecX::Zero(7)));
    problem_.add_residual_block(std::make_shared<UnitQuaternionRow>(platforms_.back()));
    std::vector<Vec3> forces{platform.mass * m.gravity()}, points{platform.center_of_mass};
    const Pose from_world = poses[p].inverse();
    for (const ExternalLoad& load : m.loads()) {
      if (m.carrying_platform(load.link) != static_cast<int>(p)) continue;
      forces.push_back(load.force);
      points.push_back(
          from_world.transform_point(m.link_pose(load.link, q, poses).transform_point(load.point)));
    }
    problem_.add_objective_term(
        std::make_shared<PlatformLoadTerm>(platforms_.back(), forces, points, energy_scale_));
  }
  for (int j : m.passive_joints()) {
    // Unbounded, as in the collocation system: the joint limits are not enforced (a minimiser held at a
    // limit would not be an equilibrium of the model, whose joints carry no limit reaction).
    passive_.push_back(problem_.add_variable_block("passive." + m.joints()[j].name, VecX::Zero(1)));
  }
  if (!passive_.empty())
    problem_.add_objective_term(std::make_shared<PassiveJointTerm>(m, q, passive_, energy_scale_));
}

void EnergyModel::add_couplings(const LinkState& links) {
  const RobotModel& m = assembly_.model();
  const VecX& q = links.joint_values;
  const std::vector<Pose>& poses = links.platform_poses;
  for (int i = 0; i < assembly_.num_rods(); ++i) {
    const RodElement& rod = m.rods()[i];
    for (const bool at_tip : {false, true}) {
      const RodAttachment& a = at_tip ? rod.end : rod.start;
      if (a.link < 0 || CouplingRows::rows_of(a.coupling) == 0) continue;
      std::vector<VariableId> variables{at_tip ? rod_points_[i].back() : rod_points_[i].front()};
      const int platform = m.carrying_platform(a.link);
      Pose platform_from_attachment;
      if (platform >= 0) {
        variables.push_back(platforms_[platform]);
        platform_from_attachment = poses[platform].inverse() * m.attachment_pose(a, q, poses);
      }
      std::vector<int> passive;
      for (std::size_t j = 0; j < m.passive_joints().size(); ++j)
        if (m.joint_moves_link(m.passive_joints()[j], a.link)) {
          passive.push_back(m.passive_joints()[j]);
          variables.push_back(passive_[j]);
        }
      problem_.add_residual_block(std::make_shared<CouplingRows>(m, a, q, platform_from_attachment, variables,
                                                                 platform >= 0 ? 1 : 0, passive,
                                                                 assembly_.length_scale()));
    }
  }
}

void EnergyModel::add_obstacle_gaps(const LinkState& links) {
  const RobotModel& m = assembly_.model();
  const VecX& q = links.joint_values;
  const std::vector<Pose>& poses = links.platform_poses;
  rod_obstacles_.resize(assembly_.num_rods());
  gap_rows_.resize(assembly_.num_rods());
  for (int i = 0; i < assembly_.num_rods(); ++i) {
    const RodContactVariables* contact = assembly_.rod_contact(i);
    if (!contact) continue;
    const std::vector<Obstacle> placed = assembly::rod_obstacles_at(m, m.rods()[i], q, poses);
    std::vector<Obstacle>& obstacles = rod_obstacles_[i];
    for (int k : contact->distributed) obstacles.push_back(placed[k]);
    const KnotVector& knots = assembly_.rod(i).knots();
    for (double u : contact->midpoints) {
      const BasisDerivatives d = basis_derivatives(knots, u, 0);
      const VecX basis = d.values.row(0).transpose();
      const std::vector<VariableId> points(rod_points_[i].begin() + d.first,
                                           rod_points_[i].begin() + d.first + basis.size());
      gap_rows_[i].push_back(problem_.add_residual_block(std::make_shared<ObstacleGapRows>(
          obstacles, contact->options.radius, basis, points, assembly_.length_scale())));
    }
  }
}

void EnergyModel::find_shared_slices() {
  const Problem& state = assembly_.problem();
  for (int i = 0; i < assembly_.num_rods(); ++i) {
    const CollocationRod& rod = assembly_.rod(i);
    const collocation::PointLayout& layout = rod.point_layout();
    for (std::size_t k = 0; k < rod_points_[i].size(); ++k) {
      const int o =
          assembly_.rod_variables(i).control_point_offset + static_cast<int>(k) * rod.control_point_size();
      const int oe = problem_.variable(rod_points_[i][k]).offset;
      shared_.push_back({o + layout.p, oe, 3});
      shared_.push_back({o + layout.q, oe + 3, 4});
    }
  }
  for (std::size_t p = 0; p < platforms_.size(); ++p)
    shared_.push_back({state.variable(assembly_.platform_variable(static_cast<int>(p))).offset,
                       problem_.variable(platforms_[p]).offset, 7});
  for (std::size_t j = 0; j < passive_.size(); ++j)
    shared_.push_back({state.variable(assembly_.passive_joint_variable(static_cast<int>(j))).offset,
                       problem_.variable(passive_[j]).offset, 1});
}

VecX EnergyModel::from_state(const VecX& x) const {
  VecX e(problem_.num_variables());
  for (const SharedSlice& s : shared_) e.segment(s.energy_offset, s.size) = x.segment(s.state_offset, s.size);
  return e;
}

void EnergyModel::to_state(const VecX& e, VecX& x, const VecX& row_multipliers) const {
  for (const SharedSlice& s : shared_) x.segment(s.state_offset, s.size) = e.segment(s.energy_offset, s.size);
  for (int i = 0; i < assembly_.num_rods(); ++i) {
    write_rod_forces(i, e, x);
    write_contact_forces(i, row_multipliers, x);
  }
}

void EnergyModel::write_contact_forces(int i, const VecX& row_multipliers, VecX& x) const {
  const RodContactVariables* contact = assembly_.rod_contact(i);
  if (!contact) return;
  const CollocationRod& rod = assembly_.rod(i);
  const RodVariables& v = assembly_.rod_variables(i);
  const Problem& state = assembly_.problem();
  const double L = rod.length(x, v), L0 = assembly_.length_scale();
  const std::vector<double> tau = rod.knots().greville();
  for (std::size_t j = 0; j < contact->midpoints.size(); ++j) {
    const Vec3 p = rod.state_at(x, v, contact->midpoints[j] * L).position;
    const int row = row_multipliers.size() ? problem_.row_offset(gap_rows_[i][j]) : -1;
    Vec3 F = Vec3::Zero();
    for (std::size_t k = 0; k < rod_obstacles_[i].size(); ++k) {
      // The minimiser's point force on the midpoint, (M0 L0 / L0) |multiplier of g / L0| nu, spread over
      // the midpoint's cell L (tau_{j+1} - tau_j) as the collocation's density.
      const double lambda = row < 0 ? 0.0
                                    : std::max(0.0, -row_multipliers[row + static_cast<int>(k)]) *
                                          energy_scale_ / L0 / (L * (tau[j + 1] - tau[j]));
      x[state.variable(contact->multipliers[j]).offset + static_cast<int>(k)] = lambda;
      F += lambda * obstacle_gap(rod_obstacles_[i][k], p, contact->options.radius).normal;
    }
    x.segment<3>(state.variable(v.contact_forces[j]).offset) = F;
  }
}

void EnergyModel::write_rod_forces(int i, const VecX& e, VecX& x) const {
  const CollocationRod& rod = assembly_.rod(i);
  const RodVariables& v = assembly_.rod_variables(i);
  const collocation::PointLayout& layout = rod.point_layout();
  const int n = rod.num_control_points(), size = rod.control_point_size();
  const RodEnergyTerm term(rod, rod.length(x, v), rod_points_[i], energy_scale_);
  std::vector<const double*> values;
  for (VariableId id : rod_points_[i]) values.push_back(e.data() + problem_.variable(id).offset);
  if (layout.integral >= 0) {  // running integrals T_0 = 0, T_{k+1} = T_k + w_k P_k (collocation_rod.hpp)
    Vec3 T = Vec3::Zero();
    for (int k = 0; k < n; ++k) {
      const int o = v.control_point_offset + k * size;
      x.segment<3>(o + layout.integral) = T;
      T += rod.integral_weights()[k] * x.segment<3>(o + layout.p);
    }
  }
  const std::vector<double> tau = rod.knots().greville();
  std::vector<Vec3> p(n), force(n), moment(n);
  for (int k = 0; k < n; ++k) term.section(values.data(), tau[k], p[k], force[k], moment[k]);
  if (layout.n >= 0) {
    // Mixed: N, M interpolate the constitutive n, m at the Greville points.
    const MatX B = MatX(collocation_matrix(rod.knots(), tau, 0));
    const Eigen::PartialPivLU<MatX> lu(B);
    MatX rhs(n, 6);
    for (int k = 0; k < n; ++k) rhs.row(k) << force[k].transpose(), moment[k].transpose();
    const MatX c = lu.solve(rhs);
    for (int k = 0; k < n; ++k) {
      const int o = v.control_point_offset + k * size;
      x.segment<3>(o + layout.n) = c.row(k).head<3>().transpose();
      x.segment<3>(o + layout.m) = c.row(k).tail<3>().transpose();
    }
  }
  if (v.wrench_offset >= 0) {
    // Condensed: n(s) = n - f s, so n = the mean of n(s) + f s; h = m(0) + (p(0) - c) x n(0).
    const Vec3 f = rod.model().distributed_force();
    const double L = rod.length(x, v);
    Vec3 n0 = Vec3::Zero();
    for (int k = 0; k < n; ++k) n0 += (force[k] + f * tau[k] * L) / n;
    x.segment<3>(v.wrench_offset) = n0;
    x.segment<3>(v.wrench_offset + 3) = moment[0] + (p[0] - rod.moment_point()).cross(n0);
  }
}

VecX EnergyModel::perturbed(const VecX& e, double size) const {
  VecX out = e;
  const double L0 = assembly_.length_scale();
  const auto move = [&](VariableId id, bool pose) {
    const VariableBlock& b = problem_.variable(id);
    for (int i = 0; i < b.size; ++i) {
      const int k = b.offset + i;
      // A fixed, irregular pattern: sin of the index at an irrational frequency.
      out[k] += size * (pose && i < 3 ? L0 : 1.0) * std::sin(2.399963 * (k + 1));
    }
  };
  for (const std::vector<VariableId>& points : rod_points_)
    for (VariableId id : points) move(id, true);
  for (VariableId id : platforms_) move(id, true);
  for (VariableId id : passive_) move(id, false);
  return out;
}

double EnergyModel::energy(const VecX& e) const {
  return problem_.evaluate_objective(e, nullptr) * energy_scale_;
}

}  // namespace pcr::kinematics
