// Scaling of forward kinematics with the number of rods: ring PCRs with 3, 6, 12, 24, 48 rods,
// generated as URDF text and parsed by parse_robot_model. Rod i is clamped at angle theta_i on a base
// circle and joined by a collar to the platform circle at theta_i +- 30 deg (alternating), so that the
// rods lean alternately left and right and hold the platform in every direction; at the default
// lengths the rods are straight and stress-free (the initial guess). Times, per model: cold = a fresh
// ForwardKinematics (assembly built outside the timing) solving the inputs shortened by 1 %, warm =
// solves cycling through three input sets about 1 mm apart that do not lie on a line, warm-started (9 per
// repeat; off a line the path predictor starts each from the last solution, whereas between two
// alternating sets it would interpolate the stored solutions exactly); medians over the
// repeats of the process CPU time. A warm solve either runs on the factorisation kept from the last
// solve (quasi-Newton steps) or takes a fresh Jacobian and factorisation (SolveSummary::
// jacobian_evaluations > 0), which costs about a cold solve's share; the two kinds are reported apart
// as well, since their mix decides the median.
// usage: bench_scaling [repeats=7]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"

namespace {

/// Process CPU time [ms]: the machine is shared, so wall time would measure the other jobs too
/// (FK is single-threaded: Eigen's sparse LU).
double cpu_ms() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

/// URDF text of a ring PCR with `rods` rods (steel, radius 1 mm, base circle 0.1 m, platform circle
/// 0.06 m at height 0.4 m, platform 0.1 kg, gravity).
std::string ring_pcr_urdf(int rods) {
  const double base_radius = 0.1, platform_radius = 0.06, height = 0.4, offset = M_PI / 6;
  std::ostringstream x;
  x.precision(12);
  x << "<?xml version=\"1.0\"?>\n<robot name=\"ring" << rods << "\">\n<link name=\"base\"/>\n"
    << "<link name=\"platform\"><inertial><origin xyz=\"0 0 0\" rpy=\"0 0 0\"/><mass value=\"0.1\"/>"
    << "<inertia ixx=\"1e-5\" ixy=\"0\" ixz=\"0\" iyy=\"1e-5\" iyz=\"0\" izz=\"2e-5\"/></inertial></link>\n"
    << "<joint name=\"platform_pose\" type=\"floating\"><parent link=\"base\"/><child link=\"platform\"/>"
    << "<origin xyz=\"0 0 " << height << "\" rpy=\"0 0 0\"/></joint>\n<pcr_gravity xyz=\"0 0 -9.81\"/>\n";
  for (int i = 0; i < rods; ++i) {
    const double theta = 2 * M_PI * i / rods, phi = theta + (i % 2 == 0 ? offset : -offset);
    const double bx = base_radius * std::cos(theta), by = base_radius * std::sin(theta);
    const double px = platform_radius * std::cos(phi), py = platform_radius * std::sin(phi);
    const double dx = px - bx, dy = py - by, length = std::sqrt(dx * dx + dy * dy + height * height);
    // Rod tangent d = (dx, dy, h) / L as the frame's z axis: R = Rz(yaw) Ry(pitch) maps e3 to
    // (cos yaw sin pitch, sin yaw sin pitch, cos pitch).
    const double pitch = std::acos(height / length), yaw = std::atan2(dy, dx);
    x << "<pcr_rod name=\"rod" << i << "\">"
      << "<start link=\"base\" xyz=\"" << bx << " " << by << " 0\" rpy=\"0 " << pitch << " " << yaw
      << "\" coupling=\"clamped\"/>"
      << "<end link=\"platform\" xyz=\"" << px << " " << py << " 0\" rpy=\"0 " << pitch << " " << yaw
      << "\" coupling=\"collar\"/>"
      << "<material youngs_modulus=\"200e9\" shear_modulus=\"80e9\" density=\"8000\"/>"
      << "<section type=\"circle\" radius=\"0.001\"/>"
      << "<length value=\"" << length << "\" actuated=\"true\" lower=\"" << 0.5 * length << "\" upper=\""
      << 1.5 * length << "\"/></pcr_rod>\n";
  }
  x << "</robot>\n";
  return x.str();
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 7;
  std::printf(
      "| rods | unknowns | cold FK [CPU ms] | cold iterations | warm FK [CPU ms] | warm iterations | warm ms "
      "per rod | warm with fresh Jacobian | warm, kept factorisation [CPU ms] | warm, fresh Jacobian "
      "[CPU ms] |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (int rods : {3, 6, 12, 24, 48}) {
    const auto model = std::make_shared<const pcr::RobotModel>(
        pcr::parse_robot_model(ring_pcr_urdf(rods), "ring" + std::to_string(rods)));
    const pcr::VecX u0 = model->default_input_values();
    const pcr::VecX u_cold = 0.99 * u0;
    // u_cold; +-1 mm alternating (the platform twists); +1 mm on every rod (it rises): a triangle in
    // input space whose sides meet at 45-90 deg
    pcr::VecX u_warm[3] = {u_cold, u_cold, u_cold};
    for (int i = 0; i < u0.size(); ++i) {
      u_warm[1][i] += (i % 2 == 0 ? 1e-3 : -1e-3);
      u_warm[2][i] += 1e-3;
    }
    std::vector<double> cold, warm, warm_kept, warm_fresh;
    int cold_iterations = 0, warm_iterations = 0, unknowns = 0;
    for (int r = 0; r < repeats; ++r) {
      pcr::ForwardKinematics fk(model);
      unknowns = static_cast<int>(fk.state().size());
      double t = cpu_ms();
      const pcr::RobotSolution s = fk.solve(u_cold);
      cold.push_back(cpu_ms() - t);
      cold_iterations = s.summary.iterations;
      if (!s.summary.converged()) {
        std::printf("ring %d: cold FK failed: %s %s\n", rods, s.summary.brief_report().c_str(),
                    s.summary.message.c_str());
        return 1;
      }
      for (int k = 0; k < 9; ++k) {
        t = cpu_ms();
        const pcr::RobotSolution w = fk.solve(u_warm[(k + 1) % 3]);
        warm.push_back(cpu_ms() - t);
        (w.summary.jacobian_evaluations > 0 ? warm_fresh : warm_kept).push_back(warm.back());
        warm_iterations = w.summary.iterations;
        if (!w.summary.converged()) {
          std::printf("ring %d: warm FK failed: %s\n", rods, w.summary.brief_report().c_str());
          return 1;
        }
      }
    }
    const double warm_ms = median(warm);
    std::printf("| %d | %d | %.2f | %d | %.2f | %d | %.3f | %zu/%zu | %.2f | %.2f |\n", rods, unknowns,
                median(cold), cold_iterations, warm_ms, warm_iterations, warm_ms / rods, warm_fresh.size(),
                warm.size(), median(warm_kept), median(warm_fresh));
    std::fflush(stdout);
  }
  return 0;
}
