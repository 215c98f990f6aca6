#pragma once
// Workspace sampling: random inputs, uniform within the model's input bounds, each solved by forward
// kinematics; the reachable platform poses and the failed samples (`pcr workspace`, docs/cli.md).
//
// Reproducible by sample: sample k of seed S has inputs from a counter-based generator keyed by (S, k)
// (workspace_sample_inputs) and is solved by a ForwardKinematics with a fresh state (as a new object:
// Newton from the model's initial guess, then the FK's fallbacks, continuation from the default inputs),
// so its result depends on (S, k) only: not on the thread that ran it, on the other samples or on how the
// samples are split between threads, processes or machines (bitwise, on one build).
//
// Threads: T workers, each with its own ForwardKinematics over one shared RobotAssembly (the Model/Data
// split of kinematics.hpp). The Newton path only: Ipopt 3.11 is not thread-safe (ipopt_solver.hpp), so
// options asking for the Ipopt solver are refused (InputError) rather than serialised.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pcr/robots/kinematics.hpp"

namespace pcr {

/// Inputs of sample `index` for `seed`, in the model's input order: input i is
/// min(upper_i, lower_i + (upper_i - lower_i) r_i) with r_i in [0, 1) the top 53 bits of the (i+1)-th
/// output of splitmix64 (Steele, Lea & Flood 2014) started at the state mix(mix(seed) ^ index), divided
/// by 2^53 (mix = splitmix64's output function). Throws InputError if an input has an unbounded range.
VecX workspace_sample_inputs(const RobotModel& model, std::uint64_t seed, std::int64_t index);

struct WorkspaceOptions {
  std::int64_t samples = 1000;    ///< how many: indices first_sample .. first_sample + samples - 1
  std::int64_t first_sample = 0;  ///< for splitting one workspace over several runs
  std::uint64_t seed = 1;
  int threads = 1;               ///< worker threads (>= 1)
  KinematicsOptions kinematics;  ///< solver must be Newton; options.assembly unused (the assembly's own)
  /// Called from the calling thread about every 0.1 s and once at the end with (samples done, total);
  /// must not throw.
  std::function<void(std::int64_t, std::int64_t)> progress;
};

struct WorkspaceSample {
  std::int64_t index = 0;
  VecX inputs;                  ///< model input order
  std::vector<Pose> platforms;  ///< world frame, model platform order (the last iterate when failed)
  SolveStatus status = SolveStatus::Failed;
  int iterations = 0, jacobian_evaluations = 0;
  double residual_max_abs = 0.0;
  double wall_time_seconds = 0.0;  ///< the only field that is not reproducible
  std::string message;             ///< the solve's message (why it failed; fallbacks taken)
  /// The verdict of a converged sample when options.kinematics.stability_verdict (robot_stability.hpp),
  /// else NotChecked.
  Stability stability;
  bool converged() const { return status == SolveStatus::Converged; }
};

struct WorkspaceResult {
  std::vector<WorkspaceSample> samples;  ///< every sample, failed ones included, in index order
  std::int64_t failures = 0;             ///< samples not converged
  std::uint64_t seed = 1;                ///< the options': what reproduces the samples
  std::int64_t first_sample = 0;
  int threads = 1;
  double wall_time_seconds = 0.0;
};

/// Sample `index` solved with a fresh state of `prototype` (its assembly and options; its own state is
/// neither used nor changed, so one prototype may serve several threads).
WorkspaceSample solve_workspace_sample(const ForwardKinematics& prototype, std::uint64_t seed,
                                       std::int64_t index);

/// The samples of `options` on `assembly`, in options.threads threads. Throws InputError for bad options
/// (samples < 0, threads < 1, Ipopt asked for, an unbounded input). A solve that throws is recorded as a
/// failed sample with the exception's message; std::bad_alloc stops the sampling and is rethrown.
WorkspaceResult sample_workspace(std::shared_ptr<const RobotAssembly> assembly,
                                 const WorkspaceOptions& options);

}  // namespace pcr
