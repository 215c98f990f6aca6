// The workspace sampler (pcr/robots/workspace.hpp): its inputs are splitmix64 draws keyed by (seed,
// index), uniform within the bounds; a sample's result depends on (seed, index) only, so 1, 2 and 3
// threads, and runs split by first_sample, give bitwise identical samples, each equal to a new
// ForwardKinematics' solve of its inputs; failed samples are kept; Ipopt and bad counts are refused.
#define BOOST_TEST_MODULE workspace
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdint>

#include "pcr/core/error.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/robots/workspace.hpp"

using namespace pcr;

namespace {

std::shared_ptr<const RobotModel> load(const std::string& name) {
  return std::make_shared<const RobotModel>(load_robot_model(std::string(PCR_MODEL_DIR) + "/" + name));
}

/// splitmix64 as published by Steele, Lea & Flood (OOPSLA 2014) and in Vigna's reference splitmix64.c,
/// written here independently of the library: state += 0x9e3779b97f4a7c15, output = mix(state).
struct SplitMix64 {
  std::uint64_t state;
  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::uint64_t next() { return mix(state += 0x9e3779b97f4a7c15ULL); }
};

bool same_sample(const WorkspaceSample& a, const WorkspaceSample& b) {
  if (a.index != b.index || a.inputs != b.inputs || a.status != b.status || a.iterations != b.iterations ||
      a.jacobian_evaluations != b.jacobian_evaluations || a.residual_max_abs != b.residual_max_abs ||
      a.message != b.message || a.platforms.size() != b.platforms.size())
    return false;
  for (size_t p = 0; p < a.platforms.size(); ++p)
    if (a.platforms[p].position != b.platforms[p].position ||
        a.platforms[p].orientation != b.platforms[p].orientation)
      return false;
  return true;
}

WorkspaceResult run(const std::shared_ptr<const RobotAssembly>& assembly, std::int64_t first,
                    std::int64_t count, int threads, std::uint64_t seed) {
  WorkspaceOptions options;
  options.first_sample = first;
  options.samples = count;
  options.threads = threads;
  options.seed = seed;
  return sample_workspace(assembly, options);
}

}  // namespace

BOOST_AUTO_TEST_CASE(sample_inputs_are_splitmix64_draws_keyed_by_seed_and_index) {
  // The reference generator against the published first outputs of splitmix64 from state 0.
  SplitMix64 zero{0};
  BOOST_CHECK_EQUAL(zero.next(), 0xe220a8397b1dcdafULL);
  BOOST_CHECK_EQUAL(zero.next(), 0x6e789e6aa1b965f4ULL);
  const auto model = load("slider_actuated.urdf");
  for (const auto& [seed, index] : {std::pair<std::uint64_t, std::int64_t>{1, 0}, {1, 7}, {12345, 99}}) {
    SplitMix64 stream{SplitMix64::mix(SplitMix64::mix(seed) ^ static_cast<std::uint64_t>(index))};
    const VecX u = workspace_sample_inputs(*model, seed, index);
    BOOST_REQUIRE_EQUAL(u.size(), 3);
    for (int i = 0; i < 3; ++i) {
      const ActuationInput& in = model->inputs()[static_cast<size_t>(i)];
      const double r = static_cast<double>(stream.next() >> 11) / 9007199254740992.0;  // / 2^53
      BOOST_CHECK_EQUAL(u[i], in.lower + (in.upper - in.lower) * r);  // exact: the same operations
    }
  }
  // Seed and index are not interchangeable.
  BOOST_CHECK(workspace_sample_inputs(*model, 2, 3) != workspace_sample_inputs(*model, 3, 2));
}

BOOST_AUTO_TEST_CASE(sample_inputs_are_uniform_within_the_bounds) {
  const auto model = load("stewart_gough.urdf");  // six rod lengths in [0.2, 0.8] m
  const int n = 20000;
  VecX sum = VecX::Zero(6), lowest = VecX::Constant(6, 1e9), highest = VecX::Constant(6, -1e9);
  for (int k = 0; k < n; ++k) {
    const VecX u = workspace_sample_inputs(*model, 42, k);
    sum += u;
    lowest = lowest.cwiseMin(u);
    highest = highest.cwiseMax(u);
  }
  for (int i = 0; i < 6; ++i) {
    // Mean of n uniform draws on [0.2, 0.8]: 0.5, standard deviation 0.6 / sqrt(12 n) = 1.2e-3 m; 4.5
    // standard deviations fail a correct generator with probability 7e-6 per input.
    BOOST_CHECK_SMALL(sum[i] / n - 0.5, 4.5 * 0.6 / std::sqrt(12.0 * n));
    BOOST_CHECK_GE(lowest[i], 0.2);
    BOOST_CHECK_LE(highest[i], 0.8);
    // The extremes of 20,000 draws lie within 0.6 * 5e-4 of the ends with probability 1 - e^-10 each.
    BOOST_CHECK_LT(lowest[i], 0.2 + 3e-4);
    BOOST_CHECK_GT(highest[i], 0.8 - 3e-4);
  }
}

BOOST_AUTO_TEST_CASE(one_two_and_three_threads_give_bitwise_identical_samples) {
  const auto assembly = std::make_shared<const RobotAssembly>(load("slider_actuated.urdf"));
  const WorkspaceResult one = run(assembly, 0, 24, 1, 11);
  const WorkspaceResult two = run(assembly, 0, 24, 2, 11);
  const WorkspaceResult three = run(assembly, 0, 24, 3, 11);
  BOOST_REQUIRE_EQUAL(one.samples.size(), 24u);
  BOOST_REQUIRE_EQUAL(two.samples.size(), 24u);
  BOOST_REQUIRE_EQUAL(three.samples.size(), 24u);
  BOOST_CHECK_EQUAL(two.threads, 2);
  for (size_t k = 0; k < 24; ++k) {
    BOOST_CHECK_EQUAL(one.samples[k].index, static_cast<std::int64_t>(k));
    BOOST_TEST(same_sample(one.samples[k], two.samples[k]), "sample " << k << ": 2 threads differ from 1");
    BOOST_TEST(same_sample(one.samples[k], three.samples[k]), "sample " << k << ": 3 threads differ from 1");
  }
  BOOST_CHECK_EQUAL(one.failures, two.failures);
  // Another seed draws other inputs.
  BOOST_CHECK(run(assembly, 0, 1, 1, 12).samples[0].inputs != one.samples[0].inputs);
}

BOOST_AUTO_TEST_CASE(split_runs_and_single_samples_reproduce_one_run) {
  const auto assembly = std::make_shared<const RobotAssembly>(load("slider_actuated.urdf"));
  const WorkspaceResult whole = run(assembly, 0, 8, 2, 5);
  const WorkspaceResult first = run(assembly, 0, 3, 1, 5), rest = run(assembly, 3, 5, 2, 5);
  BOOST_REQUIRE_EQUAL(first.samples.size() + rest.samples.size(), 8u);
  for (size_t k = 0; k < 8; ++k) {
    const WorkspaceSample& part = k < 3 ? first.samples[k] : rest.samples[k - 3];
    BOOST_TEST(same_sample(whole.samples[k], part), "sample " << k << ": the split run differs");
  }
  // A sample alone, and a new ForwardKinematics solving its inputs (the documented cold start): the same.
  const ForwardKinematics prototype(assembly);
  for (std::int64_t k : {0, 5}) {
    const WorkspaceSample alone = solve_workspace_sample(prototype, 5, k);
    BOOST_TEST(same_sample(whole.samples[static_cast<size_t>(k)], alone), "sample " << k << " alone differs");
    ForwardKinematics fresh(assembly);
    const RobotSolution s = fresh.solve(alone.inputs);
    BOOST_CHECK(s.summary.status == alone.status);
    BOOST_CHECK(s.platforms[0].position == alone.platforms[0].position);
    BOOST_CHECK(s.platforms[0].orientation == alone.platforms[0].orientation);
  }
}

BOOST_AUTO_TEST_CASE(every_sample_is_kept_and_failures_are_counted) {
  const auto assembly = std::make_shared<const RobotAssembly>(load("slider_actuated.urdf"));
  int calls = 0;
  std::int64_t last_done = -1;
  WorkspaceOptions options;
  options.samples = 10;
  options.threads = 2;
  options.progress = [&](std::int64_t done, std::int64_t total) {
    ++calls;
    BOOST_CHECK_EQUAL(total, 10);
    BOOST_CHECK_GE(done, last_done);  // never goes back
    last_done = done;
  };
  const WorkspaceResult r = sample_workspace(assembly, options);
  BOOST_REQUIRE_EQUAL(r.samples.size(), 10u);
  std::int64_t failed = 0;
  for (const WorkspaceSample& s : r.samples) {
    failed += s.converged() ? 0 : 1;
    BOOST_CHECK_EQUAL(s.platforms.size(), 1u);
    BOOST_CHECK(s.converged() || !s.message.empty());  // a failure says why
  }
  BOOST_CHECK_EQUAL(r.failures, failed);
  BOOST_CHECK_GE(calls, 1);
  BOOST_CHECK_EQUAL(last_done, 10);  // the last call reports every sample done
}

BOOST_AUTO_TEST_CASE(ipopt_and_bad_counts_are_refused) {
  const auto assembly = std::make_shared<const RobotAssembly>(load("slider_actuated.urdf"));
  WorkspaceOptions options;
  options.samples = 2;
  options.kinematics.solver = SolverKind::Ipopt;  // not thread-safe (ipopt_solver.hpp)
  BOOST_CHECK_THROW(sample_workspace(assembly, options), InputError);
  options.kinematics.solver = SolverKind::Newton;
  options.threads = 0;
  BOOST_CHECK_THROW(sample_workspace(assembly, options), InputError);
  options.threads = 1;
  options.samples = -1;
  BOOST_CHECK_THROW(sample_workspace(assembly, options), InputError);
  options.samples = 0;
  BOOST_CHECK(sample_workspace(assembly, options).samples.empty());
}

// With the verdict asked for, each converged sample carries the verdict forward kinematics gives for its
// inputs (a fresh solve with the same options), and the verdicts do not depend on the threads (the
// verdicts themselves are tested in tests/stability).
BOOST_AUTO_TEST_CASE(samples_carry_the_stability_verdict_of_their_solve) {
  const auto assembly = std::make_shared<const RobotAssembly>(load("slider_actuated.urdf"));
  WorkspaceOptions options;
  options.samples = 6;
  options.seed = 5;
  options.kinematics.stability_verdict = true;
  const WorkspaceResult one = sample_workspace(assembly, options);
  options.threads = 2;
  const WorkspaceResult two = sample_workspace(assembly, options);
  BOOST_REQUIRE_EQUAL(one.samples.size(), 6u);
  const ForwardKinematics prototype(assembly, options.kinematics);
  for (size_t k = 0; k < one.samples.size(); ++k) {
    const WorkspaceSample& s = one.samples[k];
    BOOST_REQUIRE_MESSAGE(s.converged(), "sample " << k << ": " << s.message);
    ForwardKinematics fk = prototype.with_fresh_state();
    const Stability reference = fk.solve(s.inputs).stability_verdict;
    BOOST_REQUIRE(s.stability.verdict != StabilityVerdict::NotChecked);
    BOOST_CHECK(s.stability.verdict == reference.verdict);
    BOOST_CHECK_EQUAL(s.stability.unstable_modes, reference.unstable_modes);
    BOOST_CHECK_EQUAL(s.stability.margin, reference.margin);  // the same computation: the same bits
    BOOST_CHECK(two.samples[k].stability.verdict == s.stability.verdict);
    BOOST_CHECK_EQUAL(two.samples[k].stability.margin, s.stability.margin);
  }
  // Not asked for: not checked.
  BOOST_CHECK(run(assembly, 0, 1, 1, 5).samples[0].stability.verdict == StabilityVerdict::NotChecked);
}
