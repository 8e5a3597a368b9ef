#include <gtest/gtest.h>

#include "common/error.h"
#include "io/tum.h"
#include "support/test_support.h"

namespace hdrf::io {
namespace {

using test::ExpectErrorContaining;
using test::TempDir;
using test::WriteText;

TEST(TumList, ReadsCommentsBlankLinesAndCrlf) {
  TempDir dir;
  WriteText(dir / "rgb.txt",
            "# color images\n# file: 'x.bag'\n# timestamp filename\n"
            "1305031102.175304 rgb/1305031102.175304.png\r\n\n"
            "1305031102.211214 rgb/1305031102.211214.png\n");
  const auto list = ReadImageList(dir / "rgb.txt");
  ASSERT_EQ(list.size(), 2u);
  EXPECT_DOUBLE_EQ(list[0].timestamp, 1305031102.175304);
  EXPECT_EQ(list[1].path, "rgb/1305031102.211214.png");
  EXPECT_EQ(list[1].line, 6);
}

TEST(TumList, MissingFileNamesIt) {
  TempDir dir;
  ExpectErrorContaining([&] { ReadImageList(dir / "rgb.txt"); }, {"rgb.txt", "missing"});
}

TEST(TumList, TruncatedLineNamesFileAndLine) {
  TempDir dir;
  WriteText(dir / "depth.txt", "# c\n1.0 depth/1.png\n2.0\n");
  ExpectErrorContaining([&] { ReadImageList(dir / "depth.txt"); },
                        {"depth.txt:3:", "truncated"});
}

TEST(TumList, UnparsableTimestampNamesFileAndLine) {
  TempDir dir;
  WriteText(dir / "rgb.txt", "1.0 a.png\n1.5x b.png\n");
  ExpectErrorContaining([&] { ReadImageList(dir / "rgb.txt"); },
                        {"rgb.txt:2:", "cannot parse timestamp", "1.5x"});
}

TEST(TumList, NonMonotonicTimestampsRejected) {
  TempDir dir;
  WriteText(dir / "rgb.txt", "1.0 a.png\n2.0 b.png\n2.0 c.png\n");
  ExpectErrorContaining([&] { ReadImageList(dir / "rgb.txt"); },
                        {"rgb.txt:3:", "increase strictly"});
}

TEST(TumList, NaNTimestampRejected) {
  TempDir dir;
  WriteText(dir / "rgb.txt", "nan a.png\n");
  ExpectErrorContaining([&] { ReadImageList(dir / "rgb.txt"); }, {"rgb.txt:1:", "finite"});
}

TEST(TumList, EmptyListRejected) {
  TempDir dir;
  WriteText(dir / "rgb.txt", "# only comments\n");
  ExpectErrorContaining([&] { ReadImageList(dir / "rgb.txt"); }, {"rgb.txt", "no frames"});
}

TEST(Trajectory, RoundTripIsExactToWrittenPrecision) {
  TempDir dir;
  std::vector<TimedPose> poses;
  for (int i = 0; i < 20; ++i) {
    Vec6 xi;
    xi << 0.1 * i, -0.05 * i, 0.3, 0.01 * i, -0.02 * i, 0.5 + 0.03 * i;
    poses.push_back({100.0 + i / 30.0, se3::Exp(xi)});
  }
  WriteTrajectory(dir / "t.txt", poses);
  const auto back = ReadTrajectory(dir / "t.txt");
  ASSERT_EQ(back.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(back[i].timestamp, poses[i].timestamp, 1e-6);
    EXPECT_LT((back[i].T_world_camera.translation() - poses[i].T_world_camera.translation()).norm(),
              1e-6);
    EXPECT_LT(se3::RotationAngle(back[i].T_world_camera.inverse() * poses[i].T_world_camera), 1e-8);
  }
}

TEST(Trajectory, WrongFieldCountAndNaNAndZeroQuaternion) {
  TempDir dir;
  WriteText(dir / "g.txt", "1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 1\n");
  ExpectErrorContaining([&] { ReadTrajectory(dir / "g.txt"); }, {"g.txt:2:", "truncated"});
  WriteText(dir / "g.txt", "1.0 0 0 NaN 0 0 0 1\n");
  ExpectErrorContaining([&] { ReadTrajectory(dir / "g.txt"); }, {"g.txt:1:", "tz"});
  WriteText(dir / "g.txt", "1.0 0 0 0 0 0 0 0\n");
  ExpectErrorContaining([&] { ReadTrajectory(dir / "g.txt"); }, {"g.txt:1:", "quaternion"});
  // A position no camera has (eval reported an ATE of inf from one such line).
  WriteText(dir / "g.txt", "1.0 0 0 0 0 0 0 1\n2.0 1e300 0 0 0 0 0 1\n");
  ExpectErrorContaining([&] { ReadTrajectory(dir / "g.txt"); }, {"g.txt:2:", "tx is 1e300", "at most 1e9 m"});
  WriteText(dir / "g.txt", "1.0 0 0 0 0 0 0 1\n2.0 0 -2e9 0 0 0 0 1\n");
  ExpectErrorContaining([&] { ReadTrajectory(dir / "g.txt"); }, {"g.txt:2:", "ty is -2e9"});
  WriteText(dir / "g.txt", "1.0 0 0 0 0 0 0 1\n2.0 0 0 999999999 0 0 0 1\n");
  EXPECT_EQ(ReadTrajectory(dir / "g.txt").size(), 2u);
}

TEST(Exposure, ReadsOptionalGainAndRejectsNonPositive) {
  TempDir dir;
  WriteText(dir / "exposure.txt", "# t exp gain\n1.0 12.5\n2.0 6 1.5\n");
  const auto e = ReadExposures(dir / "exposure.txt");
  ASSERT_EQ(e.size(), 2u);
  EXPECT_DOUBLE_EQ(e[0].exposure_ms, 12.5);
  EXPECT_FALSE(e[0].gain.has_value());
  EXPECT_DOUBLE_EQ(*e[1].gain, 1.5);
  WriteText(dir / "exposure.txt", "1.0 12.5\n2.0 0\n");
  ExpectErrorContaining([&] { ReadExposures(dir / "exposure.txt"); },
                        {"exposure.txt:2:", "positive"});
  WriteText(dir / "exposure.txt", "1.0 12.5 1 7\n");
  ExpectErrorContaining([&] { ReadExposures(dir / "exposure.txt"); },
                        {"exposure.txt:1:", "too many fields"});
}

TEST(Associate, ClosestPairsWithinToleranceEachUsedOnce) {
  const std::vector<double> rgb = {1.000, 1.033, 1.066, 1.200};
  const std::vector<double> depth = {1.005, 1.030, 1.031, 1.090};
  const auto m = AssociateTimestamps(rgb, depth);
  // 1.066 has nothing within 0.02 s (1.090 is 0.024 away); 1.200 neither.
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0], (std::pair<std::size_t, std::size_t>{0, 0}));
  EXPECT_EQ(m[1], (std::pair<std::size_t, std::size_t>{1, 2}));  // 0.002 beats 0.003
  EXPECT_EQ(NearestTimestamp(depth, 1.0305, 0.02).value(), 1u);
  EXPECT_FALSE(NearestTimestamp(depth, 1.2, 0.02).has_value());
}

}  // namespace
}  // namespace hdrf::io
