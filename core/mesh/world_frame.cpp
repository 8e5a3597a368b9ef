#include "mesh/world_frame.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>

namespace hdrf::mesh {

namespace {
Eigen::Vector3d V(Float3 p) { return {p.x, p.y, p.z}; }
}  // namespace

std::string WorldFrame::Describe() const {
  std::ostringstream s;
  s.precision(3);
  if (floor_found)
    s << "floor found (" << floor_area << " m^2 level), tilted " << tilt_from_camera_deg
      << " deg from the first camera's down; floor at height 0";
  else
    s << "no floor seen: up is the first camera's up, height 0 at the first camera";
  return s.str();
}

WorldFrame EstimateWorldFrame(const Mesh& m, const WorldFrameOptions& o) {
  WorldFrame wf;
  const Eigen::Vector3d hint(0, -1, 0);  // the first camera's up (its y axis points down)
  struct Tri {
    Eigen::Vector3d c, n;
    double area;
  };
  std::vector<Tri> level;
  const double cos_tilt = std::cos(o.max_tilt_deg * std::numbers::pi / 180);
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d a = V(m.position[std::size_t(t[0])]), b = V(m.position[std::size_t(t[1])]),
                          c = V(m.position[std::size_t(t[2])]);
    Eigen::Vector3d n = (b - a).cross(c - a);
    const double area = 0.5 * n.norm();
    if (!(area > 0)) continue;
    n /= 2 * area;
    // Orient by the vertex normals (into free space): a floor faces up.
    if (!m.normal.empty()) {
      const Eigen::Vector3d vn = V(m.normal[std::size_t(t[0])]) + V(m.normal[std::size_t(t[1])]) + V(m.normal[std::size_t(t[2])]);
      if (vn.dot(n) < 0) n = -n;
    }
    if (n.dot(hint) >= cos_tilt) level.push_back({(a + b + c) / 3, n, area});
  }
  Eigen::Vector3d up = hint;
  double floor_h = 0;
  if (!level.empty()) {
    // Area per 2 cm of height along the hint; the lowest height holding enough area (with
    // its neighbours) is the floor.
    constexpr double kBin = 0.02;
    std::map<long, double> hist;
    for (const Tri& t : level) hist[std::lround(t.c.dot(hint) / kBin)] += t.area;
    long floor_bin = 0;
    bool found = false;
    for (const auto& [bin, a] : hist) {
      double around = a;
      for (long d : {-1L, 1L}) {
        auto it = hist.find(bin + d);
        if (it != hist.end()) around += it->second;
      }
      if (around >= o.min_floor_area) {
        floor_bin = bin;
        found = true;
        break;
      }
    }
    if (found) {
      // Refine: the level triangles within 3 cm of the floor's height give its normal (area
      // weighted) and then its height along that normal.
      double h = double(floor_bin) * kBin;
      for (int it = 0; it < 3; ++it) {
        Eigen::Vector3d n_sum = Eigen::Vector3d::Zero();
        std::vector<const Tri*> on;
        for (const Tri& t : level)
          if (std::abs(t.c.dot(up) - h) <= 0.03) n_sum += t.area * t.n, on.push_back(&t);
        if (on.empty()) break;
        up = n_sum.normalized();
        double area = 0, h_sum = 0;
        for (const Tri* t : on) area += t->area, h_sum += t->area * t->c.dot(up);
        h = h_sum / area;
        wf.floor_area = area;
      }
      floor_h = h;
      wf.floor_found = true;
      wf.tilt_from_camera_deg = std::acos(std::clamp(up.dot(hint), -1.0, 1.0)) * 180 / std::numbers::pi;
    }
  }
  // Axes: up as asked; "forward" is the first camera's viewing direction made level.
  Eigen::Vector3d fwd = Eigen::Vector3d(0, 0, 1) - up * up.z();
  if (fwd.norm() < 1e-6) fwd = Eigen::Vector3d(1, 0, 0) - up * up.x();
  fwd.normalize();
  const Eigen::Vector3d right = fwd.cross(up).normalized();  // camera's right, level
  Eigen::Matrix3d R;  // rows: output axes in model coordinates
  if (o.up == UpAxis::kZ) {
    R.row(0) = right.transpose();  // x right
    R.row(1) = fwd.transpose();    // y forward
    R.row(2) = up.transpose();     // z up
  } else {
    R.row(0) = right.transpose();  // x right
    R.row(1) = up.transpose();     // y up
    R.row(2) = -fwd.transpose();   // z towards the viewer (glTF: the camera looks down -z)
  }
  wf.transform.block<3, 3>(0, 0) = R;
  // The first camera above the origin; the floor (or the camera) at height 0.
  const Eigen::Vector3d t = -(wf.floor_found ? floor_h : 0.0) * (o.up == UpAxis::kZ ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY());
  wf.transform.block<3, 1>(0, 3) = t;
  return wf;
}

void TransformMesh(Mesh& m, const Eigen::Matrix4d& T) {
  const Eigen::Matrix3d R = T.block<3, 3>(0, 0);
  const Eigen::Vector3d t = T.block<3, 1>(0, 3);
  for (Float3& p : m.position) {
    const Eigen::Vector3d q = R * V(p) + t;
    p = {float(q.x()), float(q.y()), float(q.z())};
  }
  for (Float3& n : m.normal) {
    const Eigen::Vector3d q = R * V(n);
    n = {float(q.x()), float(q.y()), float(q.z())};
  }
}

}  // namespace hdrf::mesh
