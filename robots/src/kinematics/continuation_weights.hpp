#pragma once
// The weights of a continuation step's predictor error (input_continuation.hpp LineSteps::
// predictor_error) on an FK state (internal header of pcr::robots).
#include "input_continuation.hpp"
#include "pcr/robots/robot_assembly.hpp"

namespace pcr::kinematics {

/// Per unknown of the assembly's state: the rods' control point positions and the platforms' positions
/// by the assembly's length scale, their quaternions as they are (rotations in rad), passive joints by
/// the length scale (prismatic) or as they are (rad); 0 for the rest (rod lengths and inputs, the
/// condensed form's wrenches and running integrals, the mixed form's forces and moments: the error
/// measures where the geometry goes, the quantity Newton's contraction region bounds).
ContinuationWeights continuation_weights(const RobotAssembly& assembly);

}  // namespace pcr::kinematics
