// hdrfusion-peers: runs other RGB-D trackers on a recorded sequence, with their documented
// default settings, for `hdrfusion-experiments tracking` to compare with. Built only where
// Debian's libopencv-contrib-dev (rgbd module) and libopen3d-dev are installed
// (tools/install_deps.sh --peers).
//
//   hdrfusion-peers SEQUENCE --out DIR [--only id,id] [--frames N]
//
// Writes DIR/<id>.txt (TUM trajectories, camera to world, world = first camera), the
// Open3D TSDF mesh of the first --tsdf-frames frames as DIR/open3d-tsdf.ply (our PLY layout; its "radiance" is the 8-bit
// colour decoded from sRGB, not HDR), and DIR/peers.json: per peer its label, wall
// seconds, frames and failed frames. Inputs are those of our engine: the colour as
// delivered (grey for the trackers that take grey), depth in metres, the intrinsics.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <cstring>
#include <nlohmann/json.hpp>
#include <open3d/camera/PinholeCameraIntrinsic.h>
#include <open3d/geometry/RGBDImage.h>
#include <open3d/geometry/TriangleMesh.h>
#include <open3d/pipelines/integration/ScalableTSDFVolume.h>
#include <open3d/pipelines/odometry/Odometry.h>
#include <open3d/utility/Logging.h>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/rgbd.hpp>
#include <sstream>

#include "common/error.h"
#include "io/ply.h"
#include "io/sequence.h"
#include "io/tum.h"

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace hdrf;

namespace {

struct Result {
  std::string id, label;
  std::vector<Pose> poses;
  double seconds = 0;
  int failed = 0;
};

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void Progress(const std::string& id, std::size_t i, std::size_t n) {
  if ((i + 1) % 100 == 0 || i + 1 == n) std::fprintf(stderr, "peers: %s %zu/%zu\n", id.c_str(), i + 1, n);
}

Pose FromMat4(const Eigen::Matrix4d& m) {
  Pose p = Pose::Identity();
  p.matrix() = m;
  return se3::Orthonormalized(p);
}

cv::Mat Grey(const ColorImage& c) {
  cv::Mat rgb(c.height(), c.width(), CV_8UC3, const_cast<Rgb8*>(&c(0, 0)));
  cv::Mat g;
  cv::cvtColor(rgb, g, cv::COLOR_RGB2GRAY);
  return g;
}
cv::Mat DepthMetres(const DepthImage& d) {
  return cv::Mat(d.height(), d.width(), CV_32F, const_cast<float*>(&d(0, 0))).clone();
}

// Frame-to-frame OpenCV odometry: src = frame k, dst = frame k-1, Rt maps k into k-1.
Result RunCvOdometry(const io::SequenceReader& seq, std::size_t n, const std::string& id,
                     const std::string& label, const cv::Ptr<cv::rgbd::Odometry>& odo) {
  Result r{id, label, {}, 0, 0};
  cv::Mat prev_grey, prev_depth;
  Pose pose = Pose::Identity(), velocity = Pose::Identity();
  double busy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const io::Frame f = seq.ReadFrame(i);
    const auto t0 = Clock::now();
    cv::Mat grey = Grey(f.color), depth = DepthMetres(f.depth_m);
    if (i > 0) {
      cv::Mat init;
      cv::eigen2cv(Eigen::Matrix4d(velocity.matrix()), init);
      cv::Mat Rt;
      Pose step = velocity;
      if (odo->compute(grey, depth, cv::Mat(), prev_grey, prev_depth, cv::Mat(), Rt, init)) {
        Eigen::Matrix4d m;
        cv::cv2eigen(Rt, m);
        step = FromMat4(m);
      } else {
        ++r.failed;
      }
      pose = se3::Orthonormalized(pose * step);
      velocity = step;
    }
    busy += Since(t0);
    r.poses.push_back(pose);
    prev_grey = grey;
    prev_depth = depth;
    Progress(id, i, n);
  }
  r.seconds = busy;
  return r;
}

// OpenCV KinectFusion: its own TSDF volume and ICP, frame to model.
Result RunKinFu(const io::SequenceReader& seq, std::size_t n) {
  Result r{"opencv-kinfu", "OpenCV KinectFusion (rgbd::kinfu, defaultParams)", {}, 0, 0};
  const SensorInfo& s = seq.sensor();
  cv::Ptr<cv::kinfu::Params> p = cv::kinfu::Params::defaultParams();
  p->frameSize = cv::Size(s.camera.width, s.camera.height);
  p->intr = cv::Matx33f(s.camera.fx, 0, s.camera.cx, 0, s.camera.fy, s.camera.cy, 0, 0, 1);
  p->rgb_intr = p->intr;
  p->depthFactor = float(s.depth_scale);
  cv::Ptr<cv::kinfu::KinFu> kf = cv::kinfu::KinFu::create(p);
  Pose last = Pose::Identity();
  Pose first_inv = Pose::Identity();
  double busy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const io::Frame f = seq.ReadFrame(i);
    cv::Mat d16(f.depth_m.height(), f.depth_m.width(), CV_16U);
    for (int y = 0; y < d16.rows; ++y)
      for (int x = 0; x < d16.cols; ++x)
        d16.at<std::uint16_t>(y, x) = std::uint16_t(std::lround(std::min(65535.0, f.depth_m(x, y) * s.depth_scale)));
    const auto t0 = Clock::now();
    const bool ok = kf->update(d16);
    busy += Since(t0);
    if (ok) {
      const cv::Matx44f m = kf->getPose().matrix;
      Eigen::Matrix4d e;
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) e(a, b) = m(a, b);
      Pose T = FromMat4(e);
      if (i == 0) first_inv = T.inverse();
      last = first_inv * T;
    } else {
      ++r.failed;  // KinFu resets itself when tracking fails; keep the last pose
    }
    r.poses.push_back(last);
    Progress(r.id, i, n);
  }
  r.seconds = busy;
  return r;
}

std::shared_ptr<open3d::geometry::RGBDImage> ToOpen3d(const io::Frame& f, double depth_scale, bool intensity) {
  open3d::geometry::Image c, d;
  c.Prepare(f.color.width(), f.color.height(), 3, 1);
  std::memcpy(c.data_.data(), &f.color(0, 0), c.data_.size());
  d.Prepare(f.depth_m.width(), f.depth_m.height(), 1, 2);
  auto* dd = reinterpret_cast<std::uint16_t*>(d.data_.data());
  for (std::size_t i = 0; i < f.depth_m.size(); ++i)
    dd[i] = std::uint16_t(std::lround(std::min(65535.0, f.depth_m[i] * depth_scale)));
  // Documented defaults except the depth scale, which is the data's (5000 units per metre).
  return open3d::geometry::RGBDImage::CreateFromColorAndDepth(c, d, depth_scale, 3.0, intensity);
}

// Open3D RGB-D odometry (hybrid photometric + geometric Jacobian), frame to frame, and
// its scalable TSDF integration of the frames at those poses (colour as delivered).
Result RunOpen3d(const io::SequenceReader& seq, std::size_t n, std::size_t tsdf_frames, const fs::path& mesh_out,
                 double* tsdf_seconds) {
  Result r{"open3d", "Open3D RGB-D odometry (hybrid term, OdometryOption defaults)", {}, 0, 0};
  open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
  const SensorInfo& s = seq.sensor();
  const open3d::camera::PinholeCameraIntrinsic intr(s.camera.width, s.camera.height, s.camera.fx, s.camera.fy,
                                                     s.camera.cx, s.camera.cy);
  // Voxel and truncation of Open3D's own RGB-D integration example (4 m / 512, 4 cm).
  open3d::pipelines::integration::ScalableTSDFVolume volume(4.0 / 512.0, 0.04,
                                                            open3d::pipelines::integration::TSDFVolumeColorType::RGB8);
  std::shared_ptr<open3d::geometry::RGBDImage> prev;
  Pose pose = Pose::Identity(), velocity = Pose::Identity();
  double busy = 0, tsdf = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const io::Frame f = seq.ReadFrame(i);
    const auto t0 = Clock::now();
    auto cur = ToOpen3d(f, s.depth_scale, true);
    if (prev) {
      const auto [ok, trans, info] = open3d::pipelines::odometry::ComputeRGBDOdometry(
          *cur, *prev, intr, Eigen::Matrix4d(velocity.matrix()));
      Pose step = velocity;
      if (ok) step = FromMat4(trans);
      else ++r.failed;
      pose = se3::Orthonormalized(pose * step);
      velocity = step;
    }
    busy += Since(t0);
    if (i < tsdf_frames) {
      const auto t1 = Clock::now();
      auto colour = ToOpen3d(f, s.depth_scale, false);
      volume.Integrate(*colour, intr, Eigen::Matrix4d(pose.inverse().matrix()));
      tsdf += Since(t1);
    }
    r.poses.push_back(pose);
    prev = cur;
    Progress(r.id, i, n);
  }
  r.seconds = busy;
  *tsdf_seconds = tsdf;
  const auto m = volume.ExtractTriangleMesh();
  mesh::Mesh out;
  for (std::size_t i = 0; i < m->vertices_.size(); ++i) {
    const Eigen::Vector3d& v = m->vertices_[i];
    out.position.push_back({float(v.x()), float(v.y()), float(v.z())});
  }
  m->ComputeVertexNormals();
  for (const auto& nrm : m->vertex_normals_) out.normal.push_back({float(nrm.x()), float(nrm.y()), float(nrm.z())});
  for (const auto& c : m->vertex_colors_) {
    auto lin = [](double s) { return float(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4)); };
    out.radiance.push_back({lin(c.x()), lin(c.y()), lin(c.z())});
  }
  for (const auto& t : m->triangles_) out.triangles.push_back({t.x(), t.y(), t.z()});
  io::WritePly(mesh_out, out);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Runs OpenCV rgbd and Open3D trackers on a sequence, for hdrfusion-experiments tracking"};
  std::string seq_dir, out, only;
  int frames = 0, tsdf_frames = 100;
  app.add_option("SEQUENCE", seq_dir, "Sequence folder (docs/formats.md)")->required();
  app.add_option("--out", out, "Output folder")->required();
  app.add_option("--only", only, "Comma-separated peers: opencv-rgbd, opencv-icp, opencv-rgbd-icp, "
                                 "opencv-kinfu, open3d (default: all)");
  app.add_option("--frames", frames, "At most this many frames (default: all)");
  app.add_option("--tsdf-frames", tsdf_frames,
                 "Open3D: integrate the first N frames into its TSDF volume at its own poses (a drifting "
                 "trajectory grows the volume without bound, so not all)")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    const io::SequenceReader seq(seq_dir);
    const std::size_t n = frames > 0 ? std::min(seq.size(), std::size_t(frames)) : seq.size();
    if (n < 2) throw InputError(seq_dir, "needs at least 2 frames");
    fs::create_directories(out);
    const std::vector<std::string> known = {"opencv-rgbd", "opencv-icp", "opencv-rgbd-icp", "opencv-kinfu", "open3d"};
    {
      std::stringstream ss(only);
      std::string t;
      while (std::getline(ss, t, ','))
        if (std::find(known.begin(), known.end(), t) == known.end())
          throw SettingError("--only", "unknown peer '" + t +
                                           "'; choose from opencv-rgbd, opencv-icp, opencv-rgbd-icp, opencv-kinfu, open3d");
    }
    auto wanted = [&](const std::string& id) {
      if (only.empty()) return true;
      std::stringstream ss(only);
      std::string t;
      while (std::getline(ss, t, ','))
        if (t == id) return true;
      return false;
    };
    const PinholeCamera& c = seq.sensor().camera;
    const cv::Mat K = (cv::Mat_<double>(3, 3) << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
    std::vector<Result> results;
    json meta = json::array();
    double tsdf_seconds = -1;
    if (wanted("opencv-rgbd"))
      results.push_back(RunCvOdometry(seq, n, "opencv-rgbd", "OpenCV RgbdOdometry (photometric, defaults)",
                                      cv::rgbd::RgbdOdometry::create(K)));
    if (wanted("opencv-icp"))
      results.push_back(RunCvOdometry(seq, n, "opencv-icp", "OpenCV ICPOdometry (defaults)",
                                      cv::rgbd::ICPOdometry::create(K)));
    if (wanted("opencv-rgbd-icp"))
      results.push_back(RunCvOdometry(seq, n, "opencv-rgbd-icp", "OpenCV RgbdICPOdometry (defaults)",
                                      cv::rgbd::RgbdICPOdometry::create(K)));
    if (wanted("opencv-kinfu")) {
      try {  // Debian builds OpenCV without OPENCV_ENABLE_NONFREE, which KinFu needs
        results.push_back(RunKinFu(seq, n));
      } catch (const cv::Exception& e) {
        std::fprintf(stderr, "peers: opencv-kinfu unavailable: %s\n", e.err.c_str());
        meta.push_back({{"id", "opencv-kinfu"}, {"label", "OpenCV KinectFusion (rgbd::kinfu)"},
                        {"unavailable", e.err}});
      }
    }
    if (wanted("open3d")) results.push_back(RunOpen3d(seq, n, std::size_t(std::max(0, tsdf_frames)), fs::path(out) / "open3d-tsdf.ply", &tsdf_seconds));
    for (const Result& r : results) {
      std::vector<io::TimedPose> tp;
      for (std::size_t i = 0; i < r.poses.size(); ++i) tp.push_back({seq.frames()[i].timestamp, r.poses[i]});
      io::WriteTrajectory(fs::path(out) / (r.id + ".txt"), tp);
      json j{{"id", r.id}, {"label", r.label}, {"seconds", r.seconds}, {"frames", r.poses.size()},
             {"failed", r.failed}};
      if (r.id == "open3d") {
        j["tsdf_seconds"] = tsdf_seconds;
        j["tsdf_frames"] = std::min<std::size_t>(n, std::size_t(std::max(0, tsdf_frames)));
      }
      meta.push_back(j);
    }
    std::ofstream js(fs::path(out) / "peers.json");
    js << json{{"sequence", seq_dir}, {"peers", meta}}.dump(2) << "\n";
    if (!js) throw InputError((fs::path(out) / "peers.json").string(), "could not be written");
    for (const Result& r : results)
      std::printf("%-16s %5zu frames  %4d failed  %7.2f s  %6.1f frames/s\n", r.id.c_str(), r.poses.size(), r.failed,
                  r.seconds, double(r.poses.size()) / std::max(1e-9, r.seconds));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hdrfusion-peers: %s\n", e.what());
    return 1;
  }
}
