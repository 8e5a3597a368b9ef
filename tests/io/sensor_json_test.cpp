#include <gtest/gtest.h>

#include <tuple>

#include "io/sensor_json.h"
#include "common/error.h"
#include "support/test_support.h"

namespace hdrf::io {
namespace {

using test::ExpectErrorContaining;
using test::TempDir;
using test::WriteText;

const char* kMinimal =
    R"({"camera": {"width": 640, "height": 480, "fx": 525.0, "fy": 525.0, "cx": 319.5,
        "cy": 239.5}, "depth": {"scale": 5000.0}, "future_key": {"x": 1}})";

std::string WithResponse(const std::string& r_values) {
  std::string g, b;
  for (int i = 0; i < 256; ++i) g += (i ? "," : "") + std::to_string(i * 0.01);
  b = g;
  return R"({"camera": {"width": 4, "height": 2, "fx": 5, "fy": 5, "cx": 1.5, "cy": 0.5},
            "depth": {"scale": 1000}, "response": {"inverse": {"r": [)" +
         r_values + "], \"g\": [" + g + "], \"b\": [" + b + "]}}}";
}

std::string Ramp(int n, int bad_at = -1, const char* bad = "") {
  std::string s;
  for (int i = 0; i < n; ++i) s += (i ? "," : "") + (i == bad_at ? bad : std::to_string(i * 0.02));
  return s;
}

TEST(SensorJson, ReadsMinimalAndIgnoresUnknownKeys) {
  TempDir dir;
  WriteText(dir / "sensor.json", kMinimal);
  const SensorInfo s = ReadSensorJson(dir / "sensor.json");
  EXPECT_EQ(s.camera.width, 640);
  EXPECT_FLOAT_EQ(s.camera.cy, 239.5f);
  EXPECT_DOUBLE_EQ(s.depth_scale, 5000.0);
  EXPECT_FALSE(s.response.has_value());
  EXPECT_FALSE(s.noise.has_value());
}

// Other generators write their own blocks, some under a name this project also uses: such a
// sequence is read (with a warning naming the file), never refused. The project's own keys
// live under "hdrfusion" and round-trip; the layout older versions wrote is still read.
TEST(SensorJson, ForeignBlocksAreIgnoredAndOwnKeysLiveUnderOneName) {
  TempDir dir;
  const std::string camera = R"("camera": {"width": 64, "height": 48, "fx": 50, "fy": 50, "cx": 31.5, "cy": 23.5},
                                 "depth": {"scale": 1000})";
  WriteText(dir / "foreign.json", "{" + camera + R"(, "synthetic": {"renderer": "blender", "noise": true}})");
  const SensorInfo foreign = ReadSensorJson(dir / "foreign.json");
  EXPECT_FALSE(foreign.synthetic.has_value());
  ASSERT_EQ(foreign.warnings.size(), 1u);
  EXPECT_NE(foreign.warnings[0].find("foreign.json"), std::string::npos) << foreign.warnings[0];
  EXPECT_NE(foreign.warnings[0].find("'synthetic'"), std::string::npos) << foreign.warnings[0];
  WriteText(dir / "odd.json", "{" + camera + R"(, "synthetic": "yes"})");
  EXPECT_EQ(ReadSensorJson(dir / "odd.json").warnings.size(), 1u);

  SensorInfo own;
  own.camera = {64, 48, 50, 50, 31.5f, 23.5f};
  own.synthetic = SensorInfo::Synthetic{"desk", 7};
  WriteSensorJson(dir / "own.json", own);
  EXPECT_NE(test::ReadText(dir / "own.json").find("\"hdrfusion\""), std::string::npos);
  const SensorInfo back = ReadSensorJson(dir / "own.json");
  ASSERT_TRUE(back.synthetic.has_value());
  EXPECT_EQ(back.synthetic->scene, "desk");
  EXPECT_EQ(back.synthetic->seed, 7u);
  EXPECT_TRUE(back.warnings.empty());

  WriteText(dir / "legacy.json", "{" + camera + R"(, "synthetic": {"scene": "room", "seed": 3}})");
  const SensorInfo legacy = ReadSensorJson(dir / "legacy.json");
  ASSERT_TRUE(legacy.synthetic.has_value());
  EXPECT_EQ(legacy.synthetic->seed, 3u);

  WriteText(dir / "bad_own.json", "{" + camera + R"(, "hdrfusion": {"synthetic": {"scene": 1}}})");
  ExpectErrorContaining([&] { ReadSensorJson(dir / "bad_own.json"); }, {"bad_own.json", "hdrfusion.synthetic"});
}

TEST(SensorJson, RoundTripWithResponseAndNoise) {
  TempDir dir;
  SensorInfo s;
  s.camera = {320, 240, 270.5f, 271.25f, 159.5f, 119.25f};
  s.depth_scale = 1000;
  radiometry::InverseResponse r;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 256; ++i) r.table[c][i] = 0.01f * float(c + 1) + 0.0371f * float(i * i);
  s.response = r;
  s.noise = radiometry::NoiseModel{{0.021f, 0.032f, 0.0213f}, {0.0001f, 0.0002f, 0.0003f}};
  WriteSensorJson(dir / "sensor.json", s);
  const SensorInfo b = ReadSensorJson(dir / "sensor.json");
  EXPECT_EQ(b.camera.width, 320);
  EXPECT_EQ(b.camera.fy, s.camera.fy);
  EXPECT_EQ(b.depth_scale, 1000);
  ASSERT_TRUE(b.response && b.noise);
  EXPECT_EQ(b.response->table, r.table);  // float -> JSON -> float is exact
  EXPECT_EQ(b.noise->sigma_s, s.noise->sigma_s);
  EXPECT_EQ(b.noise->sigma_c, s.noise->sigma_c);
}

TEST(SensorJson, DeviceBlockRoundTripsAndIsChecked) {
  TempDir dir;
  SensorInfo s;
  s.camera = {640, 480, 540, 540, 319.5f, 239.5f};
  s.device = SensorInfo::Device{"1406120314", "PrimeSense Carmine", 0.125};
  s.synthetic = SensorInfo::Synthetic{"room", 3};
  WriteSensorJson(dir / "sensor.json", s);
  const SensorInfo b = ReadSensorJson(dir / "sensor.json");
  ASSERT_TRUE(b.device && b.synthetic);  // both under "hdrfusion", neither lost
  EXPECT_EQ(b.device->serial, "1406120314");
  EXPECT_EQ(b.device->name, "PrimeSense Carmine");
  EXPECT_DOUBLE_EQ(*b.device->exposure_ms_per_unit, 0.125);
  EXPECT_EQ(b.synthetic->seed, 3u);
  const std::string base = R"({"camera": {"width": 2, "height": 2, "fx": 1, "fy": 1, "cx": 0, "cy": 0},
                               "depth": {"scale": 1000}, "hdrfusion": )";
  WriteText(dir / "a.json", base + R"({"device": {"name": "x"}}})");
  EXPECT_THROW(ReadSensorJson(dir / "a.json"), hdrf::InputError);  // no serial
  WriteText(dir / "b.json", base + R"({"device": {"serial": "s", "exposure_ms_per_unit": -1}}})");
  EXPECT_THROW(ReadSensorJson(dir / "b.json"), hdrf::InputError);
}

TEST(SensorJson, MissingFileAndInvalidJson) {
  TempDir dir;
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); }, {"sensor.json", "missing"});
  WriteText(dir / "sensor.json", "{\n \"camera\": {\n  \"width\": 640,,\n}");
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); },
                        {"sensor.json", "not valid JSON", "line 3"});
}

TEST(SensorJson, MissingRequiredKeysNamed) {
  TempDir dir;
  WriteText(dir / "sensor.json", R"({"camera": {"width": 640, "height": 480, "fx": 525, "fy": 525,
                                    "cx": 320, "cy": 240}})");
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); }, {"sensor.json", "'depth'"});
  WriteText(dir / "sensor.json", R"({"camera": {"width": 640, "fx": 525, "fy": 525, "cx": 320,
                                    "cy": 240}, "depth": {"scale": 1}})");
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); },
                        {"sensor.json", "camera.height"});
  WriteText(dir / "sensor.json", R"({"camera": {"width": 640, "height": 480, "fx": -1, "fy": 525,
                                    "cx": 320, "cy": 240}, "depth": {"scale": 1}})");
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); }, {"camera.fx", "positive"});
  // Metres per unit written where units per metre are meant (depths of kilometres).
  for (const char* scale : {"0.001", "0.01", "1e-30", "1e9"}) {
    WriteText(dir / "sensor.json", std::string(R"({"camera": {"width": 640, "height": 480, "fx": 525, "fy": 525,
                                    "cx": 320, "cy": 240}, "depth": {"scale": )") + scale + "}}");
    ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); },
                          {"sensor.json", "'depth.scale'", "units per metre"});
  }
}

// Intrinsics no lens has (a field of view outside 0.01 to 179 degrees, an image centre more
// than 85 degrees off the optical axis) are refused naming the key: the engine's loops over such a projection
// ran without end.
TEST(SensorJson, ImpossibleIntrinsicsRefusedNamingTheKey) {
  TempDir dir;
  auto with = [&](const char* fx, const char* fy, const char* cx, const char* cy) {
    WriteText(dir / "sensor.json", std::string(R"({"camera": {"width": 320, "height": 240, "fx": )") + fx +
                                       ", \"fy\": " + fy + ", \"cx\": " + cx + ", \"cy\": " + cy +
                                       R"(}, "depth": {"scale": 1000}})");
  };
  with("1e-5", "269.5", "159.5", "119.5");
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); }, {"sensor.json", "'camera.fx'", "field of view"});
  with("269.5", "1e9", "159.5", "119.5");
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); }, {"'camera.fy'", "field of view"});
  with("269.5", "269.5", "1e30", "119.5");
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); }, {"'camera.cx'", "principal point"});
  with("269.5", "269.5", "159.5", "3.5e38");
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); }, {"'camera.cy'", "principal point"});
  with("269.5", "269.5", "159.5", "-5000");
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); }, {"'camera.cy'", "85 degrees"});
  // Near the edges of the allowed ranges: 179 and 0.01 degrees across; an image centre 80
  // degrees off the axis (a crop far from a wide lens's centre).
  with("1.4", "1.1", "0", "240");
  EXPECT_NEAR(ReadSensorJson(dir / "sensor.json").camera.fx, 1.4, 1e-6);
  with("1833000", "1375000", "320", "0");
  EXPECT_NEAR(ReadSensorJson(dir / "sensor.json").camera.fy, 1375000, 1);
  with("269.5", "269.5", "1688", "119.5");
  EXPECT_NEAR(ReadSensorJson(dir / "sensor.json").camera.cx, 1688, 1e-3);
}

TEST(SensorJson, NonMonotonicResponseRejected) {
  TempDir dir;
  WriteText(dir / "sensor.json", WithResponse(Ramp(256, 200, "0.5")));
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); },
                        {"sensor.json", "channel r", "monotonic", "level 200"});
}

// A noise level out of any camera's range (1e300 became infinite as a float: the scan ran and
// failed only when it was saved) is refused when the file is read, naming the key.
TEST(SensorJson, NoiseOutOfRangeRefusedNamingTheKey) {
  TempDir dir;
  const std::string camera = R"({"camera": {"width": 4, "height": 2, "fx": 5, "fy": 5, "cx": 1.5, "cy": 0.5},
                                 "depth": {"scale": 1000}, "noise": )";
  for (const auto& [noise, key, value] :
       {std::tuple{R"({"sigma_s": [1e300, 0.03, 0.03], "sigma_c": [0.001, 0.001, 0.001]})", "noise.sigma_s", "1e+300"},
        std::tuple{R"({"sigma_s": [0.03, 0.03, 0.03], "sigma_c": [0.001, 101, 0.001]})", "noise.sigma_c", "101"},
        std::tuple{R"({"sigma_s": [0.03, -0.5, 0.03], "sigma_c": [0.001, 0.001, 0.001]})", "noise.sigma_s", "-0.5"}}) {
    WriteText(dir / "sensor.json", camera + noise + "}");
    ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); }, {"sensor.json", key, "must be 0 to 100", value});
  }
  WriteText(dir / "sensor.json", camera + R"({"sigma_s": [100, 0, 0.03], "sigma_c": [0.001, 0.001, 0.001]})" + "}");
  EXPECT_EQ(ReadSensorJson(dir / "sensor.json").noise->sigma_s[0], 100.f);
}

TEST(SensorJson, ResponseWithNaNOrWrongLengthRejected) {
  TempDir dir;
  WriteText(dir / "sensor.json", WithResponse(Ramp(256, 17, "null")));
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); },
                        {"sensor.json", "response.inverse.r[17]"});
  WriteText(dir / "sensor.json", WithResponse(Ramp(255)));
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); },
                        {"sensor.json", "256 numbers", "255"});
  WriteText(dir / "sensor.json", WithResponse(Ramp(256, 3, "NaN")));
  ExpectErrorContaining([&] { ReadSensorJson(dir / "sensor.json"); },
                        {"sensor.json", "not valid JSON"});
}

}  // namespace
}  // namespace hdrf::io
