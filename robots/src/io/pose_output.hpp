#pragma once
// A rigid-body pose in the JSON outputs, one form everywhere (internal header of pcr::robots;
// docs/results_format.md).
#include <string>

#include "pcr/robots/io/json_writer.hpp"
#include "pcr/robots/pose.hpp"

namespace pcr::io_detail {

/// position [m], quaternion_wxyz, rpy [rad] (URDF roll, pitch, yaw), world frame.
void write_pose_members(JsonWriter& json, const Pose& pose);
/// name: {position, quaternion_wxyz, rpy}.
void write_pose_object(JsonWriter& json, const std::string& name, const Pose& pose);

}  // namespace pcr::io_detail
