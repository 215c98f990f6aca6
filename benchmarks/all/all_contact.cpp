// bench_all, contact: models/planar_post.urdf (a planar robot whose pre-curved middle rod touches a round
// post, frictionless contact, docs/contact.md) by cold FK at the default inputs, the middle rod meshed
// by E elements of degree 4 (the model's hint replaced), a new solver object per solve (assembly
// included), with the post's contact distributed (the model's: densities at the midpoints) or a point
// contact (contact="point": one force at an unknown section), each solved by the semismooth Newton method
// ("newton") and by Ipopt in Scholtes' relaxation ("ipopt", AssemblyOptions::contact_method). The rod touches
// the post at one point (its radius of curvature, 0.5 m, is far above the post's, 20 mm), so both discretise
// the same problem. No closed form or independent method covers it (the shooting solver has no contact): the
// reference is the point form at E = 256, a SELF-CONVERGENCE reference that measures the discretisation
// error only where the runs are much coarser than it.
//  - contact_post_platform: error = platform position error [m];
//  - contact_post_force: error = |resultant contact force - reference| [N].
// The run's status in the progress line reads "converged;penetration" when its penetration check warned
// (the mesh does not resolve the contact; docs/contact.md).
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "all/all_runs.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"

namespace pcr::bench {

namespace {

std::shared_ptr<const RobotModel> planar_post(int elements, bool point) {
  std::ifstream file(std::string(PCR_MODEL_DIR) + "/planar_post.urdf");
  std::stringstream text;
  text << file.rdbuf();
  std::string xml = text.str();
  const std::string hint = R"(elements="24")";
  const size_t at = xml.find(hint);
  if (at == std::string::npos) return nullptr;
  xml.replace(at, hint.size(), "elements=\"" + std::to_string(elements) + "\"");
  const std::string post = R"(radius="0.02"/>)";
  const size_t post_at = xml.find(post);
  if (post_at == std::string::npos) return nullptr;
  if (point) xml.replace(post_at, post.size(), R"(radius="0.02" contact="point"/>)");
  return std::make_shared<const RobotModel>(parse_robot_model(xml, "planar_post.urdf"));
}

Vec3 contact_force(const RobotSolution& s) {
  Vec3 f = Vec3::Zero();
  for (const ObstacleContact& c : s.contacts) f += c.force;
  return f;
}

}  // namespace

bool run_contact_scenes(const AllConfig& config, Recorder& out) {
  const bool platform = config.selected("contact_post_platform"),
             force = config.selected("contact_post_force");
  if (!platform && !force) return true;
  const std::shared_ptr<const RobotModel> fine = planar_post(256, true);
  if (fine == nullptr) {
    out.note("contact_post: models/planar_post.urdf is not the expected model (elements, post); skipped");
    return false;
  }
  const RobotSolution ref = ForwardKinematics(fine).solve(fine->default_input_values());
  out.note("contact_post reference (self-convergence: point contact, E = 256): " +
           ref.summary.brief_report());
  if (!ref.summary.converged()) return false;
  const std::vector<int> meshes =
      config.quick ? std::vector<int>{8, 24, 64} : std::vector<int>{8, 12, 16, 24, 32, 48, 64, 128};
  for (int run = 0; run < 4; ++run) {
    const bool point = run % 2 == 1;
    // The contact solver: semismooth Newton (default) or Ipopt in Scholtes' relaxation (contact_ipopt.hpp).
    KinematicsOptions options;
    options.assembly.contact_method = run < 2 ? ContactMethod::Semismooth : ContactMethod::Ipopt;
    const std::string method = std::string("collocation-mixed-") + (run < 2 ? "newton" : "ipopt") +
                               (point ? "-point" : "-distributed");
    for (int elements : meshes) {
      // Ipopt takes 5-25x the time (docs/contact.md, "Solvers compared"): its runs stop at E = 48.
      if (run >= 2 && elements > 48) continue;
      // A model per timed solve, parsed outside the timing: a model keeps its default equilibrium once
      // solved (kinematics.hpp), and at the default inputs a second solve would only read it back.
      const Repeats repeats = config.repeats();
      std::vector<std::shared_ptr<const RobotModel>> models;
      for (int k = 0; k < repeats.max_count; ++k) models.push_back(planar_post(elements, point));
      size_t next = 0;
      RobotSolution sol;
      const Timing t = time_repeated(
          [&] {
            const std::shared_ptr<const RobotModel>& model = models[next++];
            sol = ForwardKinematics(model, options).solve(model->default_input_values());
          },
          repeats);
      const bool ok = sol.summary.converged();
      std::string status = to_string(sol.summary.status);
      for (const RodContactGap& g : sol.contact_gaps)
        if (g.penetrates()) status += ";penetration";
      const std::string settings = "p=4;E=" + std::to_string(elements);
      if (platform)
        out.record("contact_post_platform", method, settings,
                   ok ? (sol.platforms[0].position - ref.platforms[0].position).norm() : NAN, t,
                   sol.summary.iterations, status);
      if (force)
        out.record("contact_post_force", method, settings,
                   ok ? (contact_force(sol) - contact_force(ref)).norm() : NAN, t, sol.summary.iterations,
                   status);
    }
  }
  return true;
}

}  // namespace pcr::bench
