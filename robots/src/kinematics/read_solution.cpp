// Results of a kinematics solve read from the assembly's variables x.
#include <algorithm>

#include "../assembly/contact_assembly.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/robots/kinematics.hpp"

namespace pcr {

std::vector<std::vector<BasisDerivatives>> sample_bases(const RobotAssembly& a, int centerline_points) {
  std::vector<std::vector<BasisDerivatives>> bases;
  for (int i = 0; i < a.num_rods(); ++i)
    bases.push_back(a.rod(i).sample_basis(std::max(2, centerline_points)));
  return bases;
}

RobotSolution read_solution(const RobotAssembly& a, const VecX& x, int centerline_points) {
  return read_solution(a, x, sample_bases(a, centerline_points));
}

RobotSolution read_solution(const RobotAssembly& a, const VecX& x,
                            const std::vector<std::vector<BasisDerivatives>>& sample_bases,
                            bool with_centerline) {
  require(static_cast<int>(sample_bases.size()) == a.num_rods(), "read_solution: ", sample_bases.size(),
          " sample bases for ", a.num_rods(), " rods");
  RobotSolution s;
  s.rods.reserve(a.num_rods());
  s.inputs = a.inputs(x);
  for (size_t p = 0; p < a.model().platforms().size(); ++p)
    s.platforms.push_back(a.platform_pose(x, static_cast<int>(p)));
  s.passive_joints.resize(static_cast<int>(a.model().passive_joints().size()));
  for (int j = 0; j < s.passive_joints.size(); ++j)
    s.passive_joints[j] = x[a.problem().variable(a.passive_joint_variable(j)).offset];
  for (int i = 0; i < a.num_rods(); ++i) {
    const CollocationRod& rod = a.rod(i);
    const RodVariables& v = a.rod_variables(i);
    RodResult r;
    r.name = rod.model().name;
    r.length = rod.length(x, v);
    // Full states at the ends, the centerline and the axial stretch at every sample point (s = 0 .. L,
    // ends included).
    const std::vector<BasisDerivatives>& bases = sample_bases[i];
    const RodState b = rod.state_with_basis(x, v, 0.0, bases.front());
    const RodState t = rod.state_with_basis(x, v, r.length, bases.back());
    r.base_force = b.force;
    r.base_moment = b.moment;
    r.tip_force = t.force;
    r.tip_moment = t.moment;
    r.axial_force = b.force.dot(b.rotation.col(2));
    if (with_centerline) {
      std::vector<double> stretches;
      rod.sample_centerline(x, v, bases, r.centerline, stretches);
      r.min_axial_stretch = *std::min_element(stretches.begin(), stretches.end());
    } else {
      r.min_axial_stretch = rod.min_axial_stretch(x, v, bases);
    }
    s.rods.push_back(std::move(r));
    if (const RodContactVariables* contact = a.rod_contact(i)) {
      // Obstacles on moving links at the solution's link poses (the assembly holds their initial ones).
      RodContactVariables placed = *contact;
      placed.options.obstacles = assembly::rod_obstacles_at(
          a.model(), a.model().rods()[i], joint_values_of_solution(a.model(), s), s.platforms);
      for (ObstacleContact& c : read_rod_contact(rod, v, placed, x)) s.contacts.push_back(std::move(c));
    }
  }
  s.contact_gaps = rod_contact_gaps(s.contacts);
  return s;
}

}  // namespace pcr
