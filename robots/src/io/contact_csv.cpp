#include "contact_csv.hpp"

#include <fstream>

#include "csv_fields.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/io/obstacle_geometry.hpp"

namespace pcr::io_detail {
namespace {

std::string vector_fields(const Vec3& v, bool used) {
  std::string out;
  for (int k = 0; k < 3; ++k) out += "," + (used ? csv_number(v[k]) : std::string());
  return out;
}

void write_obstacles(const std::filesystem::path& path, const RobotModel& model,
                     const RobotSolution& solution) {
  std::ofstream file(path);
  require(static_cast<bool>(file), "write_solution_csv: cannot write '", path.string(), "'");
  file << "obstacle,type,link,x,y,z,dx,dy,dz,ex,ey,ez,radius,length\n";
  const std::vector<Obstacle> world = world_obstacles(model, solution);
  for (size_t k = 0; k < world.size(); ++k) {
    const Obstacle& o = world[k];
    const int link = model.obstacles()[k].link;
    const bool direction = o.shape == ObstacleShape::HalfSpace || o.shape == ObstacleShape::Cylinder ||
                           o.shape == ObstacleShape::Roller || (o.shape == ObstacleShape::Edge && !o.finite);
    const bool end = o.shape == ObstacleShape::Capsule || (o.shape == ObstacleShape::Edge && o.finite);
    const bool round = o.shape == ObstacleShape::Sphere || o.shape == ObstacleShape::Capsule ||
                       o.shape == ObstacleShape::Cylinder || o.shape == ObstacleShape::Roller;
    file << csv_quote(o.name) << ',' << to_string(o.shape) << ','
         << csv_quote(link < 0 ? std::string() : model.links()[link].name) << vector_fields(o.position, true)
         << vector_fields(o.direction, direction) << vector_fields(o.end, end) << ','
         << (round ? csv_number(o.radius) : "") << ','
         << (o.shape == ObstacleShape::Roller ? csv_number(o.length) : "") << '\n';
  }
  file.close();
  require(!file.fail(), "error while writing '", path.string(), "'");
}

void write_contacts(const std::filesystem::path& path, const RobotSolution& solution) {
  std::ofstream file(path);
  require(static_cast<bool>(file), "write_solution_csv: cannot write '", path.string(), "'");
  file << "rod,obstacle,concentrated,s,magnitude,gap,fx,fy,fz\n";
  for (const ObstacleContact& c : solution.contacts)
    for (size_t j = 0; j < c.arc_lengths.size(); ++j)
      file << csv_quote(c.rod) << ',' << csv_quote(c.obstacle) << ',' << (c.concentrated ? "true" : "false")
           << ',' << csv_number(c.arc_lengths[j]) << ',' << csv_number(c.densities[j]) << ','
           << csv_number(c.gaps[j]) << vector_fields(j < c.forces.size() ? c.forces[j] : Vec3::Zero(), true)
           << '\n';
  file.close();
  require(!file.fail(), "error while writing '", path.string(), "'");
}

}  // namespace

void write_contact_csv(const std::filesystem::path& dir, const RobotModel& model,
                       const RobotSolution& solution) {
  if (model.obstacles().empty()) return;
  write_obstacles(dir / "obstacles.csv", model, solution);
  write_contacts(dir / "contacts.csv", solution);
}

}  // namespace pcr::io_detail
