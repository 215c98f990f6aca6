#pragma once
// Inverse kinematics model and data (internal header of pcr::robots; kinematics.hpp "Model and data"):
// IkModel holds the problems an IK object solves, built once from the assembly and the targets and
// immutable after; IkData is one object's per-solve state.
#include <memory>
#include <vector>

#include "path_predictor.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/solve/ipopt_solver.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "reduced_ik.hpp"

namespace pcr::kinematics {

struct IkModel {
  /// Builds the problems (ik_model.cpp); throws InputError for bad targets or IK options.
  IkModel(std::shared_ptr<const RobotAssembly> assembly, const std::vector<LinkTarget>& targets,
          const KinematicsOptions& options);
  IkModel(const IkModel&) = delete;
  IkModel& operator=(const IkModel&) = delete;

  std::shared_ptr<const RobotAssembly> assembly;
  KinematicsOptions options;
  std::vector<LinkTarget> targets;
  std::vector<VariableId> target_variables;  ///< per target: its pose block [x (3), Q (4)], fixed
  std::vector<ResidualId> target_residuals;  ///< per target: its PoseTargetBlock
  /// Targets as equations, inputs free without bounds (Newton checks them afterwards). The state layout.
  Problem square;
  /// square + the input bounds, the reference inputs (a fixed block at the end, `reference`) and the
  /// input-distance objective (Ipopt over all variables).
  Problem optimised;
  VariableId reference = -1;
  /// check_stability: the FK system at an IK state (target rows off, inputs fixed); empty otherwise.
  Problem forward;
  bool square_system = false;  ///< the targets fix every degree of freedom
  bool reduced_space = false;  ///< solved in the reduced space of the inputs when Newton cannot finish
  std::shared_ptr<const ReducedIkModel> reduced;            ///< when reduced_space
  std::vector<std::vector<BasisDerivatives>> sample_bases;  ///< read_solution
};

struct IkData {
  explicit IkData(std::shared_ptr<const IkModel> model);
  IkData(const IkData&) = delete;
  IkData& operator=(const IkData&) = delete;

  const std::shared_ptr<const IkModel> model;  // first: outlives the solvers that refer into it
  VecX x;                                      // the last accepted solution, square's layout
  bool started = false;        // a solve has run (the first starts Newton from the default equilibrium)
  int last_jacobian_sign = 0;  // of the last checked converged solve (check_stability)
  PathPredictor predictor;     // start point along a path of targets
  std::unique_ptr<NewtonSolver> newton;  // on model->square, made on first use
  std::unique_ptr<IpoptSolver> ipopt;    // on model->optimised, made on first use
  std::unique_ptr<ReducedIk> reduced;    // on model->reduced
};

}  // namespace pcr::kinematics
