// Workspace sampling (workspace.hpp): counter-based inputs, one fresh FK state per sample, T worker threads
// taking sample indices from a shared counter, results stored by index.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <new>
#include <thread>

#include "pcr/core/error.hpp"
#include "pcr/robots/workspace.hpp"

namespace pcr {
namespace {

using Clock = std::chrono::steady_clock;

/// splitmix64's finaliser (Steele, Lea & Flood, "Fast splittable pseudorandom number generators",
/// OOPSLA 2014): a bijection of 64-bit words with full avalanche.
std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

constexpr std::uint64_t kGoldenGamma = 0x9e3779b97f4a7c15ULL;  // splitmix64's increment, 2^64 / phi

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// A failed sample carrying only its inputs and why.
WorkspaceSample failed_sample(std::int64_t index, VecX inputs, const std::string& message) {
  WorkspaceSample s;
  s.index = index;
  s.inputs = std::move(inputs);
  s.status = SolveStatus::Failed;
  s.message = message;
  return s;
}

void check_options(const RobotAssembly& assembly, const WorkspaceOptions& o) {
  require(o.samples >= 0, "workspace: samples = ", o.samples, " < 0");
  require(o.first_sample >= 0, "workspace: first sample = ", o.first_sample, " < 0");
  require(o.threads >= 1, "workspace: threads = ", o.threads, " < 1");
  require(o.kinematics.solver == SolverKind::Newton,
          "workspace: only the Newton solver can run in threads (Ipopt 3.11 is not thread-safe)");
  for (const ActuationInput& input : assembly.model().inputs())
    require(std::isfinite(input.lower) && std::isfinite(input.upper), "workspace: input '", input.name,
            "' has the unbounded range [", input.lower, ", ", input.upper, "]; sampling needs finite bounds");
}

/// The work shared by the threads: the next index to take, how many are done, the first bad_alloc.
struct SharedWork {
  std::atomic<std::int64_t> next{0};
  std::atomic<std::int64_t> done{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;  // guards error and wakes the caller
  std::condition_variable changed;
  std::exception_ptr error;
};

void worker(const ForwardKinematics& prototype, const WorkspaceOptions& o, SharedWork& work,
            std::vector<WorkspaceSample>& out) {
  while (!work.stop.load()) {
    const std::int64_t k = work.next.fetch_add(1);
    if (k >= o.samples) break;
    try {
      out[static_cast<size_t>(k)] = solve_workspace_sample(prototype, o.seed, o.first_sample + k);
    } catch (const std::bad_alloc&) {
      const std::lock_guard<std::mutex> lock(work.mutex);
      if (!work.error) work.error = std::current_exception();
      work.stop.store(true);
    }
    if (work.done.fetch_add(1) + 1 == o.samples) work.changed.notify_one();
  }
  if (work.stop.load()) work.changed.notify_one();
}

}  // namespace

VecX workspace_sample_inputs(const RobotModel& model, std::uint64_t seed, std::int64_t index) {
  const std::vector<ActuationInput>& inputs = model.inputs();
  VecX u(static_cast<int>(inputs.size()));
  std::uint64_t state = mix(mix(seed) ^ static_cast<std::uint64_t>(index));
  for (size_t i = 0; i < inputs.size(); ++i) {
    const ActuationInput& in = inputs[i];
    require(std::isfinite(in.lower) && std::isfinite(in.upper), "workspace: input '", in.name,
            "' has an unbounded range; sampling needs finite bounds");
    state += kGoldenGamma;
    const double r = static_cast<double>(mix(state) >> 11) * 0x1.0p-53;  // [0, 1), 53 random bits
    // lower + width r stays <= upper in floating point for r < 1 (and clamps the rounding case).
    u[static_cast<int>(i)] = std::min(in.upper, in.lower + (in.upper - in.lower) * r);
  }
  return u;
}

WorkspaceSample solve_workspace_sample(const ForwardKinematics& prototype, std::uint64_t seed,
                                       std::int64_t index) {
  VecX inputs = workspace_sample_inputs(prototype.assembly().model(), seed, index);
  // The model's default equilibrium, the start of every sample, is shared by all samples: solved here
  // (once per model) outside the sample's figures, so that they do not depend on which sample or
  // thread came first.
  prototype.default_equilibrium();
  const auto start = Clock::now();
  try {
    ForwardKinematics fk = prototype.with_fresh_state();
    const RobotSolution solution = fk.solve(inputs);
    WorkspaceSample s;
    s.index = index;
    s.inputs = std::move(inputs);
    s.platforms = solution.platforms;
    s.status = solution.summary.status;
    s.iterations = solution.summary.iterations;
    s.jacobian_evaluations = solution.summary.jacobian_evaluations;
    s.residual_max_abs = solution.summary.residual_max_abs;
    s.message = solution.summary.message;
    s.stability = solution.stability_verdict;
    s.wall_time_seconds = seconds_since(start);
    return s;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    WorkspaceSample s = failed_sample(index, std::move(inputs), std::string("error: ") + e.what());
    s.wall_time_seconds = seconds_since(start);
    return s;
  }
}

WorkspaceResult sample_workspace(std::shared_ptr<const RobotAssembly> assembly,
                                 const WorkspaceOptions& options) {
  require(assembly != nullptr, "workspace: no assembly");
  check_options(*assembly, options);
  const auto start = Clock::now();
  const ForwardKinematics prototype(std::move(assembly), options.kinematics);
  WorkspaceResult result;
  result.threads = options.threads;
  result.seed = options.seed;
  result.first_sample = options.first_sample;
  result.samples.resize(static_cast<size_t>(options.samples));
  SharedWork work;
  std::vector<std::thread> threads;
  for (int t = 0; t < options.threads; ++t)
    threads.emplace_back(worker, std::cref(prototype), std::cref(options), std::ref(work),
                         std::ref(result.samples));
  {
    // The caller's thread reports progress until every worker has finished its last sample.
    // A wake-up lost between the test and the wait costs at most one period.
    const auto finished = [&] { return work.done.load() >= options.samples || work.stop.load(); };
    std::unique_lock<std::mutex> lock(work.mutex);
    while (!finished()) {
      work.changed.wait_for(lock, std::chrono::milliseconds(100), finished);
      if (options.progress && !finished()) {
        lock.unlock();
        options.progress(work.done.load(), options.samples);
        lock.lock();
      }
    }
  }
  for (std::thread& thread : threads) thread.join();
  if (work.error) std::rethrow_exception(work.error);
  if (options.progress) options.progress(work.done.load(), options.samples);
  for (const WorkspaceSample& s : result.samples) result.failures += s.converged() ? 0 : 1;
  result.wall_time_seconds = seconds_since(start);
  return result;
}

}  // namespace pcr
