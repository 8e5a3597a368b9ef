#include "io/keyframes_io.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "io/image_io.h"
#include "io/json_file.h"
#include "io/output_file.h"
#include "io/sensor_json.h"

namespace hdrf::io {

namespace fs = std::filesystem;
using nlohmann::json;

bool HasKeyframes(const fs::path& dir) { return fs::exists(dir / "keyframes.json"); }

void WriteKeyframes(const fs::path& dir, const std::vector<pipeline::Keyframe>& keyframes, const SensorInfo& sensor,
                    int pcf_power) {
  CheckOutputFolder(dir / "keyframes");
  fs::create_directories(dir / "keyframes");
  json list = json::array();
  for (const pipeline::Keyframe& k : keyframes) {
    char name[32];
    std::snprintf(name, sizeof name, "%06d.png", k.index);
    WriteColorPng(dir / "keyframes" / name, k.color);
    json pose = json::array();
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) pose.push_back(k.T_world_camera.matrix()(i, j));
    list.push_back({{"index", k.index}, {"timestamp", k.timestamp}, {"T_world_camera", pose},
                    {"exposure_ratio", k.exposure_ratio}, {"file", std::string("keyframes/") + name}});
  }
  WriteSensorJson(dir / "sensor.json", sensor);
  const json doc = {{"format", "hdrfusion-keyframes-1"},
                    {"note", "T_world_camera: row-major 4x4, model frame (the first camera's); exposure_ratio: model "
                             "radiance / this frame's radiance"},
                    {"pcf_power", pcf_power},
                    {"keyframes", list}};
  WriteFileAtomically(dir / "keyframes.json", doc.dump(1) + "\n");
}

KeyframeSet ReadKeyframes(const fs::path& dir) {
  const fs::path file = dir / "keyframes.json";
  const json doc = ReadJsonFile(file);
  KeyframeSet set;
  set.sensor = ReadSensorJson(dir / "sensor.json");
  try {
    if (doc.value("format", "") != "hdrfusion-keyframes-1") throw InputError(file, "is not a keyframes file (format)");
    set.pcf_power = doc.at("pcf_power").get<int>();
    if (set.pcf_power < 0 || set.pcf_power > 3) throw InputError(file, "pcf_power must be 0 to 3");
    for (const json& k : doc.at("keyframes")) {
      pipeline::Keyframe f;
      f.index = k.at("index").get<int>();
      f.timestamp = k.at("timestamp").get<double>();
      const auto& p = k.at("T_world_camera");
      if (!p.is_array() || p.size() != 16) throw InputError(file, "keyframe " + std::to_string(f.index) + ": T_world_camera needs 16 numbers");
      Eigen::Matrix4d M;
      for (int i = 0; i < 16; ++i) M(i / 4, i % 4) = p[std::size_t(i)].get<double>();
      f.T_world_camera.matrix() = M;
      const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
      if (!M.allFinite() || (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-4)
        throw InputError(file, "keyframe " + std::to_string(f.index) + ": T_world_camera is not a rigid transform");
      f.exposure_ratio = k.at("exposure_ratio").get<double>();
      if (!(f.exposure_ratio > 0) || !std::isfinite(f.exposure_ratio))
        throw InputError(file, "keyframe " + std::to_string(f.index) + ": exposure_ratio must be positive");
      const std::string rel = k.at("file").get<std::string>();
      if (rel.find("..") != std::string::npos || fs::path(rel).is_absolute())
        throw InputError(file, "keyframe " + std::to_string(f.index) + ": file must lie inside the scan folder");
      // The size is checked from the header, before decoding (and again after).
      f.color = ReadColorImage(dir / rel, ExpectSize(dir / rel, set.sensor.camera.width, set.sensor.camera.height));
      set.keyframes.push_back(std::move(f));
    }
  } catch (const json::exception& e) {
    throw InputError(file, std::string("is malformed: ") + e.what());
  }
  return set;
}

}  // namespace hdrf::io
