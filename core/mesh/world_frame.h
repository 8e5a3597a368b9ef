// A world frame for export: gravity-aligned with a chosen up axis and the floor at height
// 0. The engine's model is in the first camera's frame (x right, y down, z forward); the
// camera's "down" is the first guess of gravity, refined by the floor where one is seen (the
// lowest large, level surface).
#pragma once

#include <Eigen/Core>
#include <string>

#include "mesh/mesh.h"

namespace hdrf::mesh {

enum class UpAxis { kZ, kY };  // Z-up (Blender) or Y-up (glTF)

struct WorldFrameOptions {
  UpAxis up = UpAxis::kZ;
  double min_floor_area = 0.25;  // m^2 of level surface at one height to count as a floor
  double max_tilt_deg = 25;      // how far the floor may lean from the camera's down
};

struct WorldFrame {
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();  // output <- model (first camera) frame
  bool floor_found = false;
  double floor_area = 0;          // m^2 of the surface taken as the floor
  double tilt_from_camera_deg = 0;// angle between the floor's normal and the camera's down
  std::string Describe() const;   // one line for reports
};

WorldFrame EstimateWorldFrame(const Mesh& m, const WorldFrameOptions& o = {});
// Applies a rigid transform to positions and normals, in place.
void TransformMesh(Mesh& m, const Eigen::Matrix4d& T);

}  // namespace hdrf::mesh
