// A rigid-body pose in the JSON outputs (pose_output.hpp).
#include "pose_output.hpp"

namespace pcr::io_detail {

void write_pose_members(JsonWriter& json, const Pose& pose) {
  json.key("position");
  json.array(pose.position);
  json.key("quaternion_wxyz");
  json.array(VecX(pose.orientation));
  json.key("rpy");
  json.array(pose.rpy());
}

void write_pose_object(JsonWriter& json, const std::string& name, const Pose& pose) {
  json.key(name);
  json.begin_object();
  write_pose_members(json, pose);
  json.end_object();
}

}  // namespace pcr::io_detail
