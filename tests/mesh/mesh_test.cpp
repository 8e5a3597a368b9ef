#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "common/error.h"
#include "support/sim_frames.h"
#include "support/test_support.h"
#include "imaging/imaging.h"
#include "mesh/mesh.h"
#include "volume/volume.h"

namespace hdrf {
namespace {

using test::Frames;
using test::Median;
using test::Metres;

TEST(Mesh, SphereIsAccurateAndManifold) {
  volume::VolumeOptions vo;
  vo.voxel_m = 2.0f / 64;
  volume::Volume vol(vo);
  // Integrate an analytic sphere seen from six directions (exact depth maps).
  const float R = 0.5f;
  const PinholeCamera cam{160, 120, 150.f, 150.f, 79.5f, 59.5f};
  const Vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3& d : dirs) {
    const Vec3 eye = -1.6 * d;
    const Vec3 up = std::abs(d.z()) > 0.9 ? Vec3(1, 0, 0) : Vec3(0, 0, 1);
    const Vec3 r = d.cross(up).normalized(), dn = d.cross(r);
    Pose T = Pose::Identity();
    T.linear().col(0) = r;
    T.linear().col(1) = dn;
    T.linear().col(2) = d;
    T.translation() = eye;
    DepthImage depth(160, 120, 0.f);
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x) {
        const Float3 rc = cam.BackProject(float(x), float(y), 1.f);
        const Vec3 rw = T.linear() * Vec3(rc.x, rc.y, rc.z);
        const Vec3 u = rw.normalized();
        const double b = eye.dot(u), c = eye.squaredNorm() - R * R, disc = b * b - c;
        if (disc < 0) continue;
        const double t = -b - std::sqrt(disc);
        depth(x, y) = float(t / rw.norm());
      }
    const auto v = imaging::VertexMap(depth, cam);
    const auto n = imaging::NormalMap(v);
    Image<float> one(160, 120, 1.f);
    RadianceImage rad(160, 120, Float3{1, 2, 3});
    volume::Volume::FrameInput in{&depth, &n, &rad, &one, &one, &one, cam, T};
    vol.Integrate(in);
  }
  const mesh::Mesh m = mesh::ExtractMesh(vol);
  ASSERT_GT(m.triangles.size(), 1000u);
  std::vector<double> radial;
  for (const Float3& p : m.position) radial.push_back(std::abs(double(Length(p)) - R));
  const double med = Median(radial);
  std::sort(radial.begin(), radial.end());
  const double worst = radial[radial.size() * 99 / 100];
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  const long boundary = std::count_if(edges.begin(), edges.end(), [](const auto& e) { return e.second != 2; });
  const long over = std::count_if(edges.begin(), edges.end(), [](const auto& e) { return e.second > 2; });
  std::printf("edges used once or more than twice: %ld, more than twice: %ld\n", boundary, over);
  double outward = 0;
  for (std::size_t i = 0; i < m.position.size(); ++i) outward += Dot(m.normal[i], Normalized(m.position[i]));
  std::printf("sphere mesh: %zu vertices, radial error median %.4f m, 99th percentile %.4f m (voxel "
              "%.4f), %ld of %zu edges on a hole boundary, mean normal.radial %.3f\n", m.position.size(),
              med, worst, vo.voxel_m, boundary, edges.size(), outward / double(m.position.size()));
  EXPECT_LT(med, 0.1 * vo.voxel_m);
  EXPECT_LT(worst, 0.5 * vo.voxel_m);
  EXPECT_EQ(over, 0);  // no edge shared by more than two triangles
  // Known gap: cubes with an unobserved corner are skipped, leaving small holes where the
  // six views meet at grazing angles (docs/engine.md); 420 of ~43k edges today.
  EXPECT_LT(double(boundary) / double(edges.size()), 0.02);
  EXPECT_GT(outward / double(m.position.size()), 0.99);
  EXPECT_FLOAT_EQ(m.radiance[0].y, 2.f);
}

}  // namespace
}  // namespace hdrf
