// Mesh clean-up and the export world frame: constructed meshes with every defect counted,
// and the built-in room scanned, against the scene's truth (floor at z = 0, z up).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <numbers>

#include "mesh/cleanup.h"
#include "mesh/world_frame.h"
#include "pipeline/scan_session.h"
#include "sim/synthetic_source.h"
#include "support/sim_frames.h"
#include "support/test_support.h"

namespace hdrf::mesh {
namespace {

// An n x n grid of quads `step` apart in the plane y = 0 (normal -y, the camera's up),
// radiance 1 everywhere. `skip` quads are left out (holes).
Mesh Grid(int n, float step, std::vector<std::pair<int, int>> skip = {}) {
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      m.position.push_back({i * step, 0, j * step});
      m.normal.push_back({0, -1, 0});
      m.radiance.push_back({1, 1, 1});
    }
  auto id = [n](int i, int j) { return std::int32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (std::find(skip.begin(), skip.end(), std::pair{i, j}) != skip.end()) continue;
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

TEST(MeshClean, RemovesWhatToolsChokeOnAndFillsWhatIsMissing) {
  Mesh m = Grid(10, 0.05f, {{4, 4}});  // 0.5 m square, one 5 cm quad missing (a 0.2 m hole)
  const std::size_t grid_vertices = m.position.size(), grid_triangles = m.triangles.size();
  // A duplicate of vertex 12 (a seam), used by one triangle instead of the original.
  m.position.push_back(m.position[12]);
  m.normal.push_back(m.normal[12]);
  m.radiance.push_back(m.radiance[12]);
  m.triangles[20][0] == 12 ? m.triangles[20][0] = std::int32_t(grid_vertices) : m.triangles[20][1] = std::int32_t(grid_vertices);
  m.triangles.push_back({3, 3, 4});   // degenerate (repeated vertex)
  m.triangles.push_back({0, 1, 2});   // zero area (collinear on one row)
  m.triangles.push_back(m.triangles[5]);  // a duplicate
  // A small separate piece (0.5 cm^2).
  const std::int32_t s = std::int32_t(m.position.size());
  for (Float3 p : {Float3{2, 0, 2}, Float3{2.01f, 0, 2}, Float3{2, 0, 2.01f}}) {
    m.position.push_back(p);
    m.normal.push_back({0, -1, 0});
    m.radiance.push_back({1, 1, 1});
  }
  m.triangles.push_back({s, s + 1, s + 2});
  // Radiance missing on three vertices (never seen).
  for (int v : {30, 31, 42}) m.radiance[std::size_t(v)] = {0, 0, 0};

  CleanOptions o;
  const CleanMesh c = Clean(m, o);
  const CleanReport& r = c.report;
  EXPECT_GE(r.welded, 1);
  EXPECT_EQ(r.degenerate_removed, 2);
  EXPECT_EQ(r.duplicate_removed, 1);
  EXPECT_EQ(r.pieces_removed, 1);
  EXPECT_EQ(r.pieces_kept, 1);
  EXPECT_EQ(r.holes_filled, 1);  // the 0.2 m hole; the 2 m outer border is left
  EXPECT_EQ(r.holes_left, 1);
  EXPECT_EQ(r.radiance_filled, 3);
  EXPECT_EQ(r.radiance_missing, 0);
  // What is left: the grid closed (its triangles, 4 fan triangles), one vertex more (the
  // hole's centre), every vertex with radiance, every triangle with area.
  EXPECT_EQ(c.mesh.triangles.size(), grid_triangles + 4);
  EXPECT_EQ(c.mesh.position.size(), grid_vertices + 1);
  for (std::size_t t = 0; t < c.mesh.triangles.size(); ++t) EXPECT_GT(TriangleArea(c.mesh, t), 1e-12);
  int flagged = 0;
  for (std::size_t v = 0; v < c.mesh.position.size(); ++v) {
    EXPECT_GT(Luminance(c.mesh.radiance[v]), 0.f) << v;
    flagged += c.radiance_filled[v];
  }
  EXPECT_EQ(flagged, 4);  // three filled, and the hole's centre
  const Boundary b = FindBoundary(c.mesh);
  ASSERT_EQ(b.loops.size(), 1u);  // only the outer border
  EXPECT_EQ(b.loops[0].size(), 40u);
  // Crop keeps what is inside the box.
  o.crop = Box{{-0.01f, -1, -0.01f}, {0.26f, 1, 0.26f}};
  const CleanMesh q = Clean(m, o);
  EXPECT_GT(q.report.cropped, 0);
  for (const Float3& p : q.mesh.position) EXPECT_LE(p.x, 0.26f);
  // Bad options are refused, naming them.
  o.crop = Box{{1, 1, 1}, {0, 0, 0}};
  test::ExpectErrorContaining([&] { Clean(m, o); }, {"crop"});
}

TEST(WorldFrame, TiltedFloorBecomesLevelAtHeightZero) {
  // A floor 1.2 m below the camera, tilted 10 degrees about the camera's x axis.
  Mesh m = Grid(40, 0.05f);
  const double tilt = 10 * std::numbers::pi / 180;
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.block<3, 3>(0, 0) = Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T.block<3, 1>(0, 3) = Eigen::Vector3d(-1, 1.2, 0.5);
  TransformMesh(m, T);
  for (const UpAxis up : {UpAxis::kZ, UpAxis::kY}) {
    WorldFrameOptions o;
    o.up = up;
    const WorldFrame wf = EstimateWorldFrame(m, o);
    ASSERT_TRUE(wf.floor_found);
    EXPECT_NEAR(wf.tilt_from_camera_deg, 10, 0.01);
    Mesh w = m;
    TransformMesh(w, wf.transform);
    for (std::size_t v = 0; v < w.position.size(); v += 97) {
      const float h = up == UpAxis::kZ ? w.position[v].z : w.position[v].y;
      EXPECT_NEAR(h, 0, 1e-4) << v;
      const float nu = up == UpAxis::kZ ? w.normal[v].z : w.normal[v].y;
      EXPECT_NEAR(nu, 1, 1e-5);
    }
  }
  // A mesh with no level surface: the camera's up, nothing moved up or down.
  Mesh wall = Grid(10, 0.05f);
  Eigen::Matrix4d stand = Eigen::Matrix4d::Identity();
  stand.block<3, 3>(0, 0) = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  TransformMesh(wall, stand);
  const WorldFrame none = EstimateWorldFrame(wall);
  EXPECT_FALSE(none.floor_found);
  EXPECT_NEAR(none.transform(2, 1), -1, 1e-12);  // z up is the camera's -y
}

// The built-in room scanned (150 frames), the mesh cleaned and levelled, against the
// scene's truth: the floor is z = 0 in the scene's world, z up.
TEST(MeshClean, ScannedRoomIsCleanAndLevel) {
  const auto frames = test::Frames(150, sim::AeMode::kFlicker);
  pipeline::PipelineOptions po;
  pipeline::ScanSession session(po, sim::SimCamera(320, 240), sim::SyntheticSource(sim::SimOptions()).sensor());
  for (const auto& f : frames) session.Process(test::AsInput(f));
  const Mesh raw = session.pipeline().ExtractMesh();
  const CleanMesh c = Clean(raw, {});
  const CleanReport& r = c.report;
  std::printf("room mesh: %zu -> %zu vertices, %zu -> %zu triangles; welded %d, degenerate %d, duplicate %d, pieces "
              "%d kept %d dropped, holes %d filled %d left, radiance %d filled %d missing\n",
              raw.position.size(), c.mesh.position.size(), raw.triangles.size(), c.mesh.triangles.size(), r.welded,
              r.degenerate_removed, r.duplicate_removed, r.pieces_kept, r.pieces_removed, r.holes_filled, r.holes_left,
              r.radiance_filled, r.radiance_missing);
  for (std::size_t t = 0; t < c.mesh.triangles.size(); ++t) ASSERT_GT(TriangleArea(c.mesh, t), 1e-12);
  for (const Float3& rad : c.mesh.radiance) ASSERT_GT(Luminance(rad), 0.f);
  EXPECT_EQ(r.radiance_missing, 0);
  EXPECT_LE(PieceAreas(c.mesh).size(), PieceAreas(raw).size());
  // Level: the truth's up (scene z) seen from the first camera, against the estimate.
  const Pose T0 = frames.front().T_world_camera;  // scene <- first camera
  const Eigen::Vector3d true_up = T0.rotation().transpose() * Eigen::Vector3d::UnitZ();
  const WorldFrame wf = EstimateWorldFrame(c.mesh);
  ASSERT_TRUE(wf.floor_found) << wf.Describe();
  const Eigen::Vector3d est_up = wf.transform.block<1, 3>(2, 0).transpose();
  const double angle = std::acos(std::clamp(true_up.dot(est_up), -1.0, 1.0)) * 180 / std::numbers::pi;
  // The floor's true height in the first camera's frame is -(camera height) along up.
  const double camera_height = T0.translation().z();
  const double est_camera_height = wf.transform(2, 3);  // the first camera sits at the model origin
  std::printf("world frame: %s; up within %.2f deg of the truth; first camera %.3f m above the floor (truth %.3f)\n",
              wf.Describe().c_str(), angle, est_camera_height, camera_height);
  EXPECT_LE(angle, 2.0);
  EXPECT_NEAR(est_camera_height, camera_height, 0.03);
  // Pieces per real object or wall group: how much of every scene primitive (the room's
  // walls are one group) lies on its largest piece. A vertex's primitive: the surface the
  // scene finds along its normal.
  std::vector<int> parent(c.mesh.position.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> root = [&](int v) { return parent[std::size_t(v)] == v ? v : parent[std::size_t(v)] = root(parent[std::size_t(v)]); };
  for (const auto& t : c.mesh.triangles) {
    parent[std::size_t(root(t[1]))] = root(t[0]);
    parent[std::size_t(root(t[2]))] = root(t[0]);
  }
  const sim::Scene scene = sim::Scene::Build("room", sim::SimOptions().seed);
  const RigidTransform Ts = ToRigidTransform(T0);
  std::map<int, std::map<int, long>> pieces_of;  // primitive -> piece -> vertices
  for (std::size_t v = 0; v < c.mesh.position.size(); ++v) {
    const Float3 p = Ts.Apply(c.mesh.position[v]), n = Ts.Rotate(c.mesh.normal[v]);
    const sim::Hit h = scene.Intersect(p + n * 0.03f, -n);
    if (std::abs(h.t - 0.03f) > 0.02f) continue;
    ++pieces_of[h.primitive][root(int(v))];
  }
  int objects = 0;
  for (const auto& [prim, pieces] : pieces_of) {
    long total = 0, largest = 0;
    for (const auto& [piece, n] : pieces) total += n, largest = std::max(largest, n);
    if (total < 200) continue;  // barely seen
    ++objects;
    std::printf("primitive %d: %ld vertices, %.1f %% on one piece (of %zu)\n", prim, total, 100.0 * double(largest) / double(total),
                pieces.size());
    // Measured: furniture 99.8-100 % on one piece; the walls (89.7 %, 4 pieces) and one box
    // (92.3 %, 2 pieces) are split where the scan never saw what joins their parts. The
    // goal of one piece each is not met yet (docs/export.md); this guards what holds.
    EXPECT_GE(double(largest), 0.85 * double(total)) << "primitive " << prim << " is spread over pieces";
  }
  EXPECT_GE(objects, 3);
}

}  // namespace
}  // namespace hdrf::mesh
