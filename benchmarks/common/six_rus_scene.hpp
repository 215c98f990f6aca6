#pragma once
// The 6-RUS scenes of the benchmarks (docs/benchmarks.md, Scenes, R6): models/six_rus.urdf and the
// cases of the public code of Rodrigues et al. (ARK 2024, github.com/dfki-ric-underactuated-lab/
// 6rus_cosserat_kinetostatics): their README FK inputs and IK target, their helix.
#include <memory>
#include <vector>

#include "pcr/robots/pose.hpp"
#include "pcr/robots/robot_model.hpp"

namespace pcr::bench {

/// models/six_rus.urdf with its 0.5 kg platform (their FK and helix runs), or without the platform's
/// <inertial> (massless: their README IK example).
std::shared_ptr<const RobotModel> load_six_rus(bool platform_mass = true);
/// Their README FK inputs (their published IK angles of the README IK case), rad.
VecX six_rus_readme_fk_inputs();
/// Their README IK target: platform at (0, 0, 0.5) m, roll 10 deg.
Pose six_rus_readme_ik_target();
/// Their helix (helicalTraj): radius 0.25 m about the z axis, one turn from angle 0 to 2 pi, z rising
/// linearly from 0.4 to 0.55 m, orientation identity; `points` poses (they use 500).
std::vector<Pose> six_rus_helix(int points = 200);

}  // namespace pcr::bench
