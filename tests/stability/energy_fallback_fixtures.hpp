#pragma once
// Set-ups of the energy-minimisation FK tests: an FK object's internal model and data, its default
// equilibrium, the values of a block's variables in the energy unknowns.
#include <boost/test/unit_test.hpp>
#include <memory>
#include <vector>

#include "kinematics/energy_fallback.hpp"
#include "pcr/robots/kinematics.hpp"

namespace pcr::test {

/// An FK object's model and data over `model` (the internal objects the strategies run on).
struct Fk {
  explicit Fk(const std::shared_ptr<const RobotModel>& model, KinematicsOptions o = {})
      : assembly(std::make_shared<const RobotAssembly>(model)),
        data(std::make_shared<const kinematics::FkModel>(assembly, o)) {}
  std::shared_ptr<const RobotAssembly> assembly;
  kinematics::FkData data;
};

/// The default equilibrium of fk's model (the strategy's start in these tests), required converged.
inline const VecX& default_state(const Fk& fk) {
  const DefaultEquilibrium& start = fk.data.model->default_equilibrium();
  BOOST_TEST_REQUIRE(start.converged);
  return start.x;
}

/// The values of a block's variables in the energy unknowns e.
inline std::vector<VecX> block_values(const Problem& p, const std::vector<VariableId>& variables,
                                      const VecX& e) {
  std::vector<VecX> values;
  for (VariableId id : variables) values.push_back(e.segment(p.variable(id).offset, p.variable(id).size));
  return values;
}

}  // namespace pcr::test
