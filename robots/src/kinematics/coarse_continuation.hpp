#pragma once
// The continuation in the inputs on a coarse mesh of the same rods, then Newton on the requested mesh
// (nested iteration; internal header of pcr::robots). A random FK input needs 10-20 continuation steps
// (Newton's contraction region is a few cm of rod length on the Stewart-Gough robot, docs/benchmarks.md
// "Random FK sweeps"); on the coarse mesh each step costs a fraction of one on the requested mesh, and the
// coarse equilibrium carried to the requested mesh (interpolation at its Greville abscissae) is within a
// few mm of platform position of the requested equilibrium: Newton finishes there in a few iterations.
// Where it does not converge, the continuation on the requested mesh follows (fk_strategies.cpp).
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "fk_data.hpp"
#include "input_continuation.hpp"

namespace pcr::kinematics {

/// Discretisation of the coarse mesh's rods (RodDiscretization degree and elements; the formulation as
/// the requested mesh chooses it). Degree 3 with 2 elements: random Stewart-Gough continuations took the
/// same fresh Jacobians as on the default mesh (degree 6, 8 elements) at 0.3x the time per solve, and
/// its equilibria were within 2.5 mm (median) and 2 cm (worst of 40) of platform position of the default
/// mesh's (docs/benchmarks.md "Random FK sweeps").
constexpr int kCoarseDegree = 3;
constexpr int kCoarseElements = 2;
/// The coarse stage is used only where it has at most this share of the requested mesh's unknowns.
constexpr double kCoarseMaxVariableShare = 0.6;

/// A state of one assembly carried to another of the same model (another mesh of the same rods): per rod
/// the control points interpolated at the target's Greville abscissae (the same curve where the target's
/// spline space contains the source's), every other variable block copied by name (platform poses,
/// joints, inputs, rod lengths, a condensed rod's wrench, contact multipliers). A rod with obstacles must
/// keep its knots (its contact rows sit at the knot spans' midpoints).
class MeshTransfer {
 public:
  MeshTransfer() = default;
  /// valid() is false when the assemblies do not match block for block (then apply must not be called).
  MeshTransfer(const RobotAssembly& from, const RobotAssembly& to);
  bool valid() const { return valid_; }
  /// The state `from_x` of `from` as a state of `to` (size: to's variables).
  VecX apply(const VecX& from_x) const;

 private:
  struct RodMap {
    int from_offset, to_offset, from_points, to_points, point_size;
    MatX interpolation;  // to_points x from_points: control points of `to` from those of `from`
  };
  struct BlockCopy {
    int from_offset, to_offset, size;
  };
  bool valid_ = false;
  int to_size_ = 0;
  std::vector<RodMap> rods_;
  std::vector<BlockCopy> copies_;
};

/// The coarse mesh of an FK model: its FkModel (its own shared default equilibrium) and the transfers.
struct CoarseMesh {
  std::shared_ptr<const FkModel> model;
  MeshTransfer to_fine, to_coarse;
  ContinuationWeights weights;  // of the coarse assembly (continuation_weights.hpp)
};

/// Built on first use, once per FkModel (thread-safe); nullptr where the coarse stage does not apply
/// (not Newton, rods with contact, no fewer unknowns, blocks that do not match).
class SharedCoarseMesh {
 public:
  const CoarseMesh* get(const FkModel& fine);

 private:
  std::once_flag built_;
  std::unique_ptr<const CoarseMesh> mesh_;
};

/// Budget of fresh Jacobians of the Newton on the requested mesh from the transferred state.
constexpr int kFineNewtonJacobians = 4;

/// One FK object's coarse-mesh data: its solver state on the coarse mesh, and the coarse equilibrium
/// behind its last result (a warm start for the next continuation from the last solution).
struct CoarseStage {
  explicit CoarseStage(std::shared_ptr<const FkModel> coarse) : data(std::move(coarse)) {}
  FkData data;       // on the coarse FkModel; data.x: the coarse equilibrium behind fine_result
  VecX fine_result;  // the equilibrium of the requested mesh the last coarse stage returned (empty: none)
  int fine_jacobians = kFineNewtonJacobians;  // budget of the Newton on the requested mesh
};

/// Outcome of one coarse-mesh continuation and its Newton on the requested mesh.
struct CoarseOutcome {
  bool converged = false;
  SolveSummary last;  // of the Newton on the requested mesh (or of the stage that failed)
  int steps = 0, iterations = 0, jacobian_evaluations = 0;  // of both meshes
  int fine_jacobians = 0;                                   // of the Newton on the requested mesh
  std::string stopped;                                      // why it did not converge
};

/// Continuation on the coarse mesh from the default inputs (x_from == nullptr: the coarse default
/// equilibrium) or from the equilibrium x_from of the requested mesh at inputs u0, to `inputs`, then
/// Newton on the requested mesh; on success x holds the requested mesh's equilibrium. `continuation`
/// runs the coarse continuation (the caller's step control) on the coarse data's solve.
using CoarseContinuation = std::function<ContinuationResult(
    FkData& coarse, const ContinuationWeights& weights, const VecX& u0, VecX& x_coarse)>;
CoarseOutcome coarse_then_fine(FkData& data, const VecX& u0, const VecX* x_from, const VecX& inputs, VecX& x,
                               const CoarseContinuation& continuation);

/// Where a direct Newton attempt on the coarse mesh starts: a state of the requested mesh carried there,
/// the coarse default equilibrium, or the coarse assembly's straight initial guess.
enum class CoarseStart { FineState, DefaultEquilibrium, StraightGuess };

/// A direct attempt probed on the coarse mesh: Newton at `inputs` on the coarse mesh (at most
/// coarse_jacobians fresh Jacobians) from `start` (x_from: the state of the requested mesh for
/// CoarseStart::FineState), then Newton on the requested mesh from the coarse equilibrium carried there.
/// stopped empty and not converged: no coarse mesh (the caller solves on the requested mesh).
CoarseOutcome coarse_direct(FkData& data, CoarseStart start, const VecX* x_from, const VecX& inputs, VecX& x,
                            int coarse_jacobians);

/// Whether the model has a coarse mesh (builds it on first use).
bool has_coarse_mesh(const FkData& data);

}  // namespace pcr::kinematics
