// bench_all (issue #7): run time against error of every method on every scene, into ONE CSV
//   scene,method,settings,error,time_median_s,time_min_s,time_max_s,iterations,time_mean_s
// Methods: collocation (primal, mixed and condensed form, Newton and Ipopt paths, degree p and E elements
// per rod)
// and shooting (RK4 with N steps per rod, adaptive Dormand-Prince 5(4) with tolerance tol).
// Scenes: R1_phi_2pi, R2_alpha_10, R3_helix, spring_20deg (single rods, cold solves), R5a_fk_cold,
// R5a_ik_cold (Stewart-Gough, cold: a new solver object per solve), R5b_ik_path (teleoperation path,
// time per warm-started IK solve), R5b_helix_path (the same on a helix of 400 new targets),
// contact_post_platform and contact_post_force (planar_post.urdf FK over meshes; all_contact.cpp).
// Error of each run against a reference computed in this run by an INDEPENDENT method, never the run's
// own: the analytic solution where one exists (R1, R3 centerline, R2 elastica tip); otherwise
// collocation runs against tight shooting (Dormand-Prince 1e-12) and shooting runs against tight
// collocation (mixed, degree 8). Failed solves have error nan.
// usage: bench_all [--quick] [--scenes R1,R5b,...] [--out PATH]   (default benchmarks/results/all.csv)
//   --quick: reduced sweeps for smoke runs; --scenes: name prefixes (R1, R2, R3, spring, R5a, R5a_fk, R5b,
//   R5b_helix, contact).
// Reports: scripts/bench_report.sh PATH (PNGs with Pareto fronts, Markdown tables).
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>

#include "all/all_runs.hpp"

using namespace pcr::bench;

namespace {

int usage(const char* message) {
  std::fprintf(
      stderr,
      "bench_all: %s\nusage: bench_all [--quick] [--scenes R1,R2,R3,spring,R5a,R5b,contact] [--out PATH]\n",
      message);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  AllConfig config;
  std::string out = "benchmarks/results/all.csv";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      config.quick = true;
    } else if ((arg == "--scenes" || arg == "--out") && i + 1 < argc) {
      const std::string value = argv[++i];
      if (arg == "--out") {
        out = value;
      } else {
        std::stringstream list(value);
        for (std::string name; std::getline(list, name, ',');)
          if (!name.empty()) config.scenes.push_back(name);
        if (config.scenes.empty()) return usage("--scenes needs at least one name");
      }
    } else {
      return usage(("unknown or incomplete argument '" + arg + "'").c_str());
    }
  }
  Recorder recorder(out);
  if (!recorder.ok()) {
    std::fprintf(stderr, "bench_all: cannot write %s\n", out.c_str());
    return 1;
  }
  const bool rods_ok = run_rod_scenes(config, recorder);
  const bool robots_ok = run_robot_scenes(config, recorder);
  const bool contact_ok = run_contact_scenes(config, recorder);
  if (recorder.rows() == 0) return usage("no scene matches --scenes");
  recorder.note("wrote " + std::to_string(recorder.rows()) + " rows to " + out);
  return rods_ok && robots_ok && contact_ok ? 0 : 1;
}
