#include "stress/solution_consistency.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "pcr/robots/io/solution_writers.hpp"

namespace pcr::test {
namespace {

/// The passive joints' balances recomputed from the solution at the joint values q into c (the largest
/// |Q - k (q - rest)| of revolute and of prismatic joints), Q = w . sum ((x - o) x F + M) (revolute) or w .
/// sum F (prismatic) over the wrenches on the links the joint moves: rod ends (+n(0), +m(0) on a start link;
/// -n(L), -m(L) on an end link), link weights and loads (docs/model_format.md, "Passive joints").
void check_passive_balances(const RobotModel& model, const RobotSolution& s, const VecX& q, Consistency& c) {
  for (int j : model.passive_joints()) {
    const Joint& joint = model.joints()[j];
    const Pose frame = model.link_pose(joint.parent_link, q, s.platforms) * joint.origin;
    const Vec3 w = frame.rotation() * joint.axis, o = frame.position;
    Vec3 F = Vec3::Zero(), M = Vec3::Zero();
    auto add = [&](const Vec3& x, const Vec3& force, const Vec3& torque) {
      F += force;
      M += (x - o).cross(force) + torque;
    };
    for (size_t l = 0; l < model.links().size(); ++l)
      if (model.joint_moves_link(j, static_cast<int>(l)) && model.links()[l].mass > 0.0)
        add(model.link_pose(static_cast<int>(l), q, s.platforms)
                .transform_point(model.links()[l].center_of_mass),
            model.links()[l].mass * model.gravity(), Vec3::Zero());
    for (const ExternalLoad& load : model.loads())
      if (model.joint_moves_link(j, load.link))
        add(model.link_pose(load.link, q, s.platforms).transform_point(load.point), load.force, load.torque);
    for (size_t i = 0; i < s.rods.size(); ++i) {
      const RodResult& r = s.rods[i];
      if (model.rods()[i].start.link >= 0 && model.joint_moves_link(j, model.rods()[i].start.link))
        add(r.centerline.front(), r.base_force, r.base_moment);
      if (model.rods()[i].end.link >= 0 && model.joint_moves_link(j, model.rods()[i].end.link))
        add(r.centerline.back(), -r.tip_force, -r.tip_moment);
    }
    const bool prismatic = joint.type == JointType::Prismatic;
    const double Q = w.dot(prismatic ? F : M);
    const double residual = Q - joint.stiffness * (q[joint.value_index] - joint.rest);
    double& worst = prismatic ? c.passive_force : c.passive_moment;
    worst = std::max(worst, std::abs(residual));
  }
}

// Every number of the solution is finite.
bool all_finite(const RobotSolution& s) {
  bool finite = s.inputs.allFinite();
  for (const Pose& p : s.platforms) finite = finite && p.position.allFinite() && p.orientation.allFinite();
  for (const RodResult& r : s.rods) {
    finite = finite && std::isfinite(r.length) && r.base_force.allFinite() && r.base_moment.allFinite() &&
             r.tip_force.allFinite() && r.tip_moment.allFinite() && std::isfinite(r.axial_force);
    for (const Vec3& p : r.centerline) finite = finite && p.allFinite();
  }
  return finite;
}

}  // namespace

/// Recomputes, from the RobotSolution alone (and the model), what a converged result must satisfy.
/// Sign conventions (kinematics.hpp, docs/design.md §3): the rod exerts +n(0), +m(0) on its start link at
/// p(0) and -n(L), -m(L) on its end link at p(L); platform balance about the platform origin x:
///   m g + F_ext + sum_start n(0) - sum_end n(L) = 0,
///   (R c) x m g + sum (r_load x F + T) + sum_start [m(0) + (p(0) - x) x n(0)]
///                                      - sum_end [m(L) + (p(L) - x) x n(L)] = 0.
Consistency check_solution(const RobotModel& model, const RobotSolution& s) {
  Consistency c;
  c.finite = all_finite(s);
  if (!c.finite) return c;

  // Every moving joint's value: the joint inputs' and the passive joints' (RobotSolution::passive_joints).
  const VecX joint_values = joint_values_of_solution(model, s);
  const size_t np = model.platforms().size();
  std::vector<Vec3> force(np, Vec3::Zero()), moment(np, Vec3::Zero());
  std::vector<double> magnitude(np, 0.0);  // sum of |force terms|, for the round-off bound
  for (size_t p = 0; p < np; ++p) {
    const Platform& pl = model.platforms()[p];
    const Vec3 weight = pl.mass * model.gravity();
    force[p] += weight;
    moment[p] += (s.platforms[p].rotation() * pl.center_of_mass).cross(weight);
    magnitude[p] += weight.norm();
  }
  for (const ExternalLoad& l : model.loads()) {
    const int p = model.carrying_platform(l.link);
    if (p < 0) continue;
    const Pose link = model.link_pose(l.link, joint_values, s.platforms);
    force[p] += l.force;
    moment[p] += (link.transform_point(l.point) - s.platforms[p].position).cross(l.force) + l.torque;
    magnitude[p] += l.force.norm();
  }
  for (size_t i = 0; i < s.rods.size(); ++i) {
    const RodElement& e = model.rods()[i];
    const RodResult& r = s.rods[i];
    // Inputs: the rod-length inputs are the rods' lengths.
    for (size_t k = 0; k < model.inputs().size(); ++k)
      if (model.inputs()[k].kind == ActuationInput::Kind::RodLength &&
          model.inputs()[k].index == static_cast<int>(i))
        c.length = std::max(c.length, std::abs(r.length - s.inputs[k]));
    // Couplings: every attached end sits at its attachment point (all coupling kinds fix p).
    const Vec3 ends[2] = {r.centerline.front(), r.centerline.back()};
    const RodAttachment* att[2] = {&e.start, &e.end};
    for (int k = 0; k < 2; ++k) {
      if (att[k]->link < 0 || att[k]->coupling == RodEndKind::Free) continue;
      const Pose frame = model.attachment_pose(*att[k], joint_values, s.platforms);
      c.coupling = std::max(c.coupling, (ends[k] - frame.position).norm());
      const int p = model.carrying_platform(att[k]->link);
      if (p < 0) continue;
      const double sigma = k == 0 ? 1.0 : -1.0;  // start: +n(0); end: -n(L)
      const Vec3& n = k == 0 ? r.base_force : r.tip_force;
      const Vec3& m = k == 0 ? r.base_moment : r.tip_moment;
      force[p] += sigma * n;
      moment[p] += sigma * (m + (ends[k] - s.platforms[p].position).cross(n));
      magnitude[p] += n.norm();
    }
    // Arc length: |p'| = |e3 + eps| <= 1 + |n| / min(K_SE), |n| largest at an end (n' = -f is
    // constant), so the centerline polyline (shorter than the curve) is at most
    // L (1 + max|n| / min K_SE) for an exact solution; the excess measures the discretisation error
    // (the constitutive law holds only at the collocation points).
    double polyline = 0.0;
    for (size_t k = 1; k < r.centerline.size(); ++k)
      polyline += (r.centerline[k] - r.centerline[k - 1]).norm();
    const double n_max = std::max(r.base_force.norm(), r.tip_force.norm());
    const double bound = r.length * (1.0 + n_max / e.rod.shear_extension_stiffness.minCoeff());
    c.stretch = std::max(c.stretch, polyline / bound - 1.0);
  }
  check_passive_balances(model, s, joint_values, c);
  for (size_t p = 0; p < np; ++p) {
    c.force = std::max(c.force, force[p].norm());
    c.moment = std::max(c.moment, moment[p].norm());
    c.magnitude = std::max(c.magnitude, magnitude[p]);
  }
  return c;
}

}  // namespace pcr::test
