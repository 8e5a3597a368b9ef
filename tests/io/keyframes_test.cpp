// Keyframes: which frames a scan keeps (motion steps, thinning past the cap), their files
// round-trip, and malformed files are refused naming the file.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "io/keyframes_io.h"
#include "pipeline/keyframes.h"
#include "sim/synthetic_source.h"
#include "support/test_support.h"

namespace hdrf::io {
namespace {

pipeline::FrameReport Moved(int index, double x_m, bool fused = true) {
  pipeline::FrameReport r;
  r.index = index;
  r.fused = fused;
  r.T_world_camera = Pose::Identity();
  r.T_world_camera.translation() = Eigen::Vector3d(x_m, 0, 0);
  r.exposure_ratio = 1 + 0.01 * index;
  return r;
}

TEST(Keyframes, KeptAfterEnoughMotionAndThinnedPastTheCap) {
  pipeline::KeyframeOptions o;
  o.min_translation_m = 0.08;
  o.max_keyframes = 4;
  pipeline::KeyframeSelector sel(o);
  const ColorImage img(8, 6, Rgb8{10, 20, 30});
  // 3 cm per frame: a keyframe every third frame (9 cm), lost frames never.
  std::vector<int> kept;
  for (int i = 0; i < 10; ++i)
    if (sel.Offer(Moved(i, 0.03 * i, i != 3), img)) kept.push_back(i);
  EXPECT_EQ(kept, (std::vector<int>{0, 4, 7}));  // 3 is not fused; 4 is 12 cm from 0
  EXPECT_EQ(sel.thinned(), 0);
  // The fifth keyframe exceeds the cap: every other one kept, the step doubled to 16 cm.
  EXPECT_TRUE(sel.Offer(Moved(10, 0.30), img));
  EXPECT_TRUE(sel.Offer(Moved(13, 0.39), img));
  EXPECT_EQ(sel.thinned(), 1);
  ASSERT_EQ(sel.keyframes().size(), 3u);
  EXPECT_EQ(sel.keyframes()[1].index, 7);
  EXPECT_FALSE(sel.Offer(Moved(14, 0.50), img));  // 11 cm < 16 cm
  EXPECT_TRUE(sel.Offer(Moved(15, 0.56), img));
  EXPECT_NEAR(sel.keyframes().back().exposure_ratio, 1.15, 1e-12);
  pipeline::KeyframeOptions bad;
  bad.max_keyframes = 1;
  EXPECT_THROW(pipeline::KeyframeSelector{bad}, SettingError);
}

TEST(Keyframes, RoundTripAndRefuseMalformedFilesNamingThem) {
  test::TempDir dir;
  const SensorInfo sensor = sim::SyntheticSource(sim::SimOptions()).sensor();
  std::vector<pipeline::Keyframe> ks;
  for (int i = 0; i < 2; ++i) {
    pipeline::Keyframe k;
    k.index = 5 * i;
    k.timestamp = 0.1 * i;
    k.T_world_camera.translation() = Eigen::Vector3d(0.1 * i, 0, 0);
    k.exposure_ratio = 0.5 + i;
    k.color = ColorImage(sensor.camera.width, sensor.camera.height, Rgb8{std::uint8_t(40 * i), 90, 200});
    ks.push_back(std::move(k));
  }
  WriteKeyframes(dir.path(), ks, sensor, 2);
  const KeyframeSet back = ReadKeyframes(dir.path());
  ASSERT_EQ(back.keyframes.size(), 2u);
  EXPECT_EQ(back.pcf_power, 2);
  EXPECT_EQ(back.keyframes[1].index, 5);
  EXPECT_DOUBLE_EQ(back.keyframes[1].exposure_ratio, 1.5);
  EXPECT_NEAR(back.keyframes[1].T_world_camera.translation().x(), 0.1, 1e-12);
  EXPECT_EQ(back.keyframes[1].color(3, 4), (Rgb8{40, 90, 200}));
  EXPECT_EQ(back.sensor.camera.width, sensor.camera.width);
  // Malformed: each refusal names the file.
  const auto doc = nlohmann::json::parse(test::ReadText(dir.path() / "keyframes.json"));
  const auto refused = [&](nlohmann::json d, const std::string& file, const std::string& what) {
    test::WriteText(dir.path() / "keyframes.json", d.dump());
    try {
      ReadKeyframes(dir.path());
      ADD_FAILURE() << "accepted: " << what;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  auto d = doc;
  d["keyframes"][0]["T_world_camera"][0] = 2.0;
  refused(d, "keyframes.json", "rigid");
  d = doc;
  d["keyframes"][1]["exposure_ratio"] = -1;
  refused(d, "keyframes.json", "exposure_ratio");
  d = doc;
  d["keyframes"][0]["file"] = "../../etc/passwd";
  refused(d, "keyframes.json", "inside the scan folder");
  d = doc;
  d["keyframes"][0].erase("timestamp");
  refused(d, "keyframes.json", "malformed");
  d = doc;
  d["keyframes"][1]["file"] = "keyframes/missing.png";
  refused(d, "missing.png", "missing");
}

}  // namespace
}  // namespace hdrf::io
