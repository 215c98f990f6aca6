#include "pcr/robots/io/obstacle_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pcr/core/error.hpp"
#include "pcr/robots/io/robot_outline.hpp"

namespace pcr {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSegments = 12;  // facets around a round surface: coarse, enough to see the shape

/// Two unit vectors normal to the unit vector a and to each other.
void normal_basis(const Vec3& a, Vec3& e1, Vec3& e2) {
  const Vec3 helper = std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  e1 = a.cross(helper).normalized();
  e2 = a.cross(e1);
}

int add_point(ObstacleMesh& mesh, const Vec3& x) {
  mesh.points.push_back(x);
  return static_cast<int>(mesh.points.size()) - 1;
}

/// kSegments points of the circle of `radius` around `centre` normal to the unit axis a; first index.
int add_ring(ObstacleMesh& mesh, const Vec3& centre, const Vec3& a, double radius) {
  Vec3 e1, e2;
  normal_basis(a, e1, e2);
  const int first = static_cast<int>(mesh.points.size());
  for (int k = 0; k < kSegments; ++k) {
    const double phi = 2.0 * kPi * k / kSegments;
    add_point(mesh, centre + radius * (std::cos(phi) * e1 + std::sin(phi) * e2));
  }
  return first;
}

/// The side of the tube of `radius` around the segment x0 x1: kSegments quads; with end discs (closed
/// kSegments-gons) when `caps`.
void add_tube(ObstacleMesh& mesh, const Vec3& x0, const Vec3& x1, double radius, bool caps) {
  const Vec3 a = (x1 - x0).normalized();
  const int r0 = add_ring(mesh, x0, a, radius), r1 = add_ring(mesh, x1, a, radius);
  for (int k = 0; k < kSegments; ++k) {
    const int next = (k + 1) % kSegments;
    mesh.polygons.push_back({r0 + k, r0 + next, r1 + next, r1 + k});
  }
  if (!caps) return;
  for (int r : {r0, r1}) {
    std::vector<int> disc;
    for (int k = 0; k < kSegments; ++k) disc.push_back(r + k);
    mesh.polygons.push_back(disc);
  }
}

/// A sphere of kSegments longitudes and kSegments / 2 latitude bands around the unit axis a (triangles at
/// the poles, quads between), or only its half on the side of +a (from its equator ring on).
void add_sphere(ObstacleMesh& mesh, const Vec3& centre, double radius, const Vec3& a, bool half) {
  const int bands = kSegments / 2;
  std::vector<int> rings;
  for (int b = half ? bands / 2 : 1; b < bands; ++b) {
    const double latitude = -0.5 * kPi + kPi * b / bands;
    rings.push_back(add_ring(mesh, centre + radius * std::sin(latitude) * a, a, radius * std::cos(latitude)));
  }
  const int north = add_point(mesh, centre + radius * a);
  const int south = half ? -1 : add_point(mesh, centre - radius * a);
  for (int k = 0; k < kSegments; ++k) {
    const int next = (k + 1) % kSegments;
    if (!half) mesh.polygons.push_back({south, rings.front() + next, rings.front() + k});
    for (size_t b = 0; b + 1 < rings.size(); ++b)
      mesh.polygons.push_back({rings[b] + k, rings[b] + next, rings[b + 1] + next, rings[b + 1] + k});
    mesh.polygons.push_back({rings.back() + k, rings.back() + next, north});
  }
}

/// The centerline point of all rods nearest to the obstacle (by its gap with zero rod radius), or the
/// obstacle's position when there is no centerline point.
Vec3 nearest_rod_point(const Obstacle& obstacle, const RobotSolution& solution) {
  Vec3 best = obstacle.position;
  double best_gap = std::numeric_limits<double>::infinity();
  for (const RodResult& rod : solution.rods)
    for (const Vec3& x : rod.centerline) {
      const double g = obstacle_gap(obstacle, x, 0.0).gap;
      if (g < best_gap) best_gap = g, best = x;
    }
  return best;
}

/// The diagonal of the rods' bounding box, at least 1 mm.
double robot_size(const RobotSolution& solution) {
  Vec3 lower = Vec3::Constant(std::numeric_limits<double>::infinity()), upper = -lower;
  for (const RodResult& rod : solution.rods)
    for (const Vec3& x : rod.centerline) lower = lower.cwiseMin(x), upper = upper.cwiseMax(x);
  const double d = (upper - lower).norm();
  return std::isfinite(d) ? std::max(d, 1e-3) : 1e-3;
}

ObstacleMesh obstacle_mesh(const Obstacle& o, const RobotSolution& solution, double size) {
  ObstacleMesh mesh;
  mesh.name = o.name;
  const Vec3 near = nearest_rod_point(o, solution);
  // The foot of `near` on an infinite axis through o.position along o.direction.
  const Vec3 foot = o.position + o.direction * o.direction.dot(near - o.position);
  switch (o.shape) {
    case ObstacleShape::HalfSpace: {
      Vec3 e1, e2;
      normal_basis(o.direction, e1, e2);
      const Vec3 centre = near - o.direction * o.direction.dot(near - o.position);
      const double h = 0.5 * size;
      for (const auto& [s1, s2] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
        add_point(mesh, centre + h * (s1 * e1 + s2 * e2));
      mesh.polygons.push_back({0, 1, 2, 3});
      break;
    }
    case ObstacleShape::Sphere: add_sphere(mesh, o.position, o.radius, Vec3::UnitZ(), false); break;
    case ObstacleShape::Capsule:
      add_tube(mesh, o.position, o.end, o.radius, false);
      add_sphere(mesh, o.position, o.radius, (o.position - o.end).normalized(), true);
      add_sphere(mesh, o.end, o.radius, (o.end - o.position).normalized(), true);
      break;
    case ObstacleShape::Cylinder:
      add_tube(mesh, foot - 0.5 * size * o.direction, foot + 0.5 * size * o.direction, o.radius, false);
      break;
    case ObstacleShape::Roller:
      add_tube(mesh, o.position - 0.5 * o.length * o.direction, o.position + 0.5 * o.length * o.direction,
               o.radius, true);
      break;
    case ObstacleShape::Edge:
      if (o.finite) {
        mesh.lines.push_back({add_point(mesh, o.position), add_point(mesh, o.end)});
      } else {
        mesh.lines.push_back({add_point(mesh, foot - 0.5 * size * o.direction),
                              add_point(mesh, foot + 0.5 * size * o.direction)});
      }
      break;
    case ObstacleShape::Point: mesh.vertices.push_back(add_point(mesh, o.position)); break;
  }
  return mesh;
}

/// The centerline of `rod` at arc length s, linearly interpolated between its equally spaced points.
Vec3 centerline_at(const RodResult& rod, double s) {
  const int n = static_cast<int>(rod.centerline.size());
  if (n == 1 || rod.length <= 0.0) return rod.centerline.front();
  const double t = std::clamp(s / rod.length, 0.0, 1.0) * (n - 1);
  const int i = std::min(static_cast<int>(t), n - 2);
  return rod.centerline[i] + (t - i) * (rod.centerline[i + 1] - rod.centerline[i]);
}

}  // namespace

std::vector<Obstacle> world_obstacles(const RobotModel& model, const RobotSolution& solution) {
  VecX q = joint_values_of_inputs(model, solution.inputs);
  const std::vector<int>& passive = model.passive_joints();
  if (solution.passive_joints.size() == static_cast<int>(passive.size()))
    for (size_t i = 0; i < passive.size(); ++i)
      q[model.joints()[passive[i]].value_index] = solution.passive_joints[static_cast<int>(i)];
  std::vector<Obstacle> out;
  for (const ObstacleElement& e : model.obstacles()) {
    if (e.link < 0) {
      out.push_back(e.obstacle);
      continue;
    }
    const Pose pose = model.link_pose(e.link, q, solution.platforms);
    out.push_back(e.obstacle.transformed(pose.rotation(), pose.position));
  }
  return out;
}

std::vector<ObstacleMesh> obstacle_meshes(const RobotModel& model, const RobotSolution& solution) {
  const std::vector<Obstacle> obstacles = world_obstacles(model, solution);
  const double size = robot_size(solution);
  std::vector<ObstacleMesh> meshes;
  for (size_t k = 0; k < obstacles.size(); ++k) {
    meshes.push_back(obstacle_mesh(obstacles[k], solution, size));
    meshes.back().obstacle = static_cast<int>(k);
  }
  return meshes;
}

ContactForceSamples contact_force_samples(const RobotSolution& solution) {
  ContactForceSamples out;
  for (const RodResult& rod : solution.rods) {
    out.nodal.emplace_back(rod.centerline.size(), Vec3::Zero());
    out.density.emplace_back(rod.centerline.size(), Vec3::Zero());
  }
  for (const ObstacleContact& c : solution.contacts) {
    const auto rod = std::find_if(solution.rods.begin(), solution.rods.end(),
                                  [&](const RodResult& r) { return r.name == c.rod; });
    require(rod != solution.rods.end(), "contact_force_samples: contact of rod '", c.rod, "' with obstacle '",
            c.obstacle, "' names no rod of the solution");
    const int r = static_cast<int>(rod - solution.rods.begin());
    const int n = static_cast<int>(rod->centerline.size());
    if (c.concentrated) {
      if (!c.intervals.empty() && !c.arc_lengths.empty() && n > 0) {
        out.points.push_back(centerline_at(*rod, c.arc_lengths[0]));
        out.forces.push_back(c.force);
        out.rods.push_back(r);
      }
      continue;
    }
    if (n == 0) continue;
    // Centerline point i sits at s_i = i L / (n - 1); cell j's midpoint at arc_lengths[j].
    for (size_t j = 0; j < c.forces.size() && j < c.arc_lengths.size(); ++j) {
      const double t = rod->length > 0.0 ? c.arc_lengths[j] / rod->length : 0.0;
      const int i = std::clamp(static_cast<int>(std::lround(t * (n - 1))), 0, n - 1);
      out.nodal[r][i] += c.forces[j];
    }
    for (int i = 0; i < n; ++i) {  // the density of the cell whose midpoint is nearest to s_i
      const double s = n > 1 ? rod->length * i / (n - 1) : 0.0;
      size_t nearest = 0;
      for (size_t j = 1; j < c.arc_lengths.size(); ++j)
        if (std::abs(c.arc_lengths[j] - s) < std::abs(c.arc_lengths[nearest] - s)) nearest = j;
      if (nearest < c.forces.size() && c.forces[nearest].norm() > 0.0)
        out.density[r][i] += c.densities[nearest] * c.forces[nearest].normalized();
    }
  }
  return out;
}

}  // namespace pcr
