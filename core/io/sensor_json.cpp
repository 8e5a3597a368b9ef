#include "io/sensor_json.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/error.h"
#include "common/message.h"
#include "io/json_file.h"
#include "io/output_file.h"

namespace hdrf::io {

using nlohmann::json;

namespace {

const json& Require(const std::filesystem::path& file, const json& obj, const char* key,
                    const std::string& where) {
  if (!obj.is_object() || !obj.contains(key))
    throw InputError(file, "missing required key '" + where + key + "'");
  return obj.at(key);
}

double Number(const std::filesystem::path& file, const json& v, const std::string& key) {
  if (!v.is_number()) throw InputError(file, "'" + key + "' must be a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw InputError(file, "'" + key + "' is not a finite number");
  return d;
}

double Positive(const std::filesystem::path& file, const json& v, const std::string& key) {
  const double d = Number(file, v, key);
  if (!(d > 0)) throw InputError(file, "'" + key + "' must be positive");
  return d;
}

// JSON has no NaN; nlohmann reads a literal NaN as a syntax error and null where a number
// belongs means a writer put NaN there, so both are reported as "not a finite number".
constexpr double kMaxNoiseSigma = 100;

std::array<float, 3> Triple(const std::filesystem::path& file, const json& v,
                            const std::string& key) {
  if (!v.is_array() || v.size() != 3)
    throw InputError(file, "'" + key + "' must be an array of 3 numbers [r, g, b]");
  std::array<float, 3> out{};
  for (int c = 0; c < 3; ++c) {
    const double d = Number(file, v[c], key + "[" + std::to_string(c) + "]");
    // In the response's units (mid-grey radiance 1): a noise of 100 is no camera's, and 1e300
    // became infinite as a float and failed the scan only when it was saved.
    if (!(d >= 0 && d <= kMaxNoiseSigma))
      throw InputError(file, "'" + key + "' must be 0 to " + std::to_string(int(kMaxNoiseSigma)) +
                                 " (in the response's units, mid-grey radiance 1), got " + v[c].dump());
    out[c] = float(d);
  }
  return out;
}

}  // namespace

SensorInfo ReadSensorJson(const std::filesystem::path& file) { return SensorFromJson(file, ReadJsonFile(file)); }

SensorInfo SensorFromJson(const std::filesystem::path& file, const json& j) {
  if (!j.is_object()) throw InputError(file, "the sensor must be a JSON object");

  SensorInfo s;
  const json& cam = Require(file, j, "camera", "");
  const double w = Positive(file, Require(file, cam, "width", "camera."), "camera.width");
  const double h = Positive(file, Require(file, cam, "height", "camera."), "camera.height");
  if (w != std::floor(w) || h != std::floor(h) || w > 65535 || h > 65535)
    throw InputError(file, "'camera.width' and 'camera.height' must be whole pixel counts");
  s.camera.width = int(w);
  s.camera.height = int(h);
  s.camera.fx = float(Positive(file, Require(file, cam, "fx", "camera."), "camera.fx"));
  s.camera.fy = float(Positive(file, Require(file, cam, "fy", "camera."), "camera.fy"));
  s.camera.cx = float(Number(file, Require(file, cam, "cx", "camera."), "camera.cx"));
  s.camera.cy = float(Number(file, Require(file, cam, "cy", "camera."), "camera.cy"));
  // A pinhole camera's focal length gives its field of view, and the principal point where
  // the optical axis meets the image. Beyond a field of view of 0.01 to 179 degrees across
  // the image, or a principal point more than an image size outside the image that also puts
  // the image centre more than 85 degrees off the axis, the projection is
  // meaningless (and the engine's loops over it ran without end), so such values are refused.
  auto focal = [&](const char* key, double f, double size) {
    const double lo = size / (2 * std::tan(89.5 * M_PI / 180)), hi = size / (2 * std::tan(0.005 * M_PI / 180));
    if (f < lo || f > hi)
      throw InputError(file, "'camera." + std::string(key) + "' is " + json(f).dump() + " pixels: with an image " +
                                 json(int(size)).dump() + " pixels across that is not a field of view of 0.01 to "
                                 "179 degrees (it must be between " + json(std::ceil(lo * 1000) / 1000).dump() +
                                 " and " + json(std::floor(hi)).dump() + ")");
  };
  focal("fx", s.camera.fx, w);
  focal("fy", s.camera.fy, h);
  auto centre = [&](const char* key, double c, double f, double size) {
    const double reach = std::max(1.5 * size, f * std::tan(85 * M_PI / 180));
    if (std::fabs(c - size / 2) > reach)
      throw InputError(file, "'camera." + std::string(key) + "' is " + json(c).dump() +
                                 ": that principal point lies more than an image size outside the image and "
                                 "puts its centre more than 85 degrees off the optical axis (it must be between " + json(std::ceil(size / 2 - reach)).dump() +
                                 " and " + json(std::floor(size / 2 + reach)).dump() + ")");
  };
  centre("cx", s.camera.cx, s.camera.fx, w);
  centre("cy", s.camera.cy, s.camera.fy, h);
  const json& depth = Require(file, j, "depth", "");
  s.depth_scale = Positive(file, Require(file, depth, "scale", "depth."), "depth.scale");
  // Raw depth units per metre: 1000 for millimetres, 5000 for TUM-style recordings. Below 1
  // a unit would be longer than a metre (a 16-bit image would reach beyond 65 km): almost
  // certainly metres per unit written where units per metre are meant.
  if (s.depth_scale < 1 || s.depth_scale > 1e6)
    throw InputError(file, "'depth.scale' is " + json(s.depth_scale).dump() +
                               ": it is raw depth units per metre (1000 for millimetres, 5000 for TUM-style "
                               "depth), between 1 and 1000000");

  if (j.contains("response")) {
    const json& inv = Require(file, j["response"], "inverse", "response.");
    radiometry::InverseResponse r;
    const char* ch[3] = {"r", "g", "b"};
    for (int c = 0; c < 3; ++c) {
      const std::string key = std::string("response.inverse.") + ch[c];
      const json& t = Require(file, inv, ch[c], "response.inverse.");
      if (!t.is_array() || t.size() != 256)
        throw InputError(file, "'" + key + "' must be an array of 256 numbers, found " +
                                   (t.is_array() ? std::to_string(t.size()) : "no array"));
      for (int i = 0; i < 256; ++i)
        r.table[c][i] = float(Number(file, t[i], key + "[" + std::to_string(i) + "]"));
    }
    r.Check(file.string());
    s.response = r;
  }
  if (j.contains("noise")) {
    const json& n = j["noise"];
    radiometry::NoiseModel m;
    m.sigma_s = Triple(file, Require(file, n, "sigma_s", "noise."), "noise.sigma_s");
    m.sigma_c = Triple(file, Require(file, n, "sigma_c", "noise."), "noise.sigma_c");
    s.noise = m;
  }
  // The project's own keys live under "hdrfusion"; every other block belongs to whoever wrote
  // it and is ignored (a warning where it uses a name the project knows).
  if (j.contains("hdrfusion")) {
    const json& own = j["hdrfusion"];
    if (!own.is_object()) throw InputError(file, "'hdrfusion' must be an object");
    if (own.contains("synthetic")) {
      const json& syn = own["synthetic"];
      if (!syn.is_object() || !syn.contains("scene") || !syn["scene"].is_string() || !syn.contains("seed") ||
          !syn["seed"].is_number_unsigned() || syn["seed"].get<std::uint64_t>() > 0xffffffffull)
        throw InputError(file, "'hdrfusion.synthetic' must be {\"scene\": name, \"seed\": unsigned 32-bit number}");
      s.synthetic = SensorInfo::Synthetic{syn["scene"].get<std::string>(), syn["seed"].get<std::uint32_t>()};
    }
    if (own.contains("device")) {
      const json& dev = own["device"];
      if (!dev.is_object() || !dev.contains("serial") || !dev["serial"].is_string())
        throw InputError(file, "'hdrfusion.device' must be an object with a string 'serial'");
      SensorInfo::Device d;
      d.serial = dev["serial"].get<std::string>();
      if (dev.contains("name")) {
        if (!dev["name"].is_string()) throw InputError(file, "'hdrfusion.device.name' must be a string");
        d.name = dev["name"].get<std::string>();
      }
      if (dev.contains("exposure_ms_per_unit"))
        d.exposure_ms_per_unit =
            Positive(file, dev["exposure_ms_per_unit"], "hdrfusion.device.exposure_ms_per_unit");
      s.device = d;
    }
  }
  if (j.contains("synthetic")) {
    // Sequences written before the "hdrfusion" block held {"scene", "seed"} here; other
    // generators write blocks of their own under this name.
    const json& syn = j["synthetic"];
    const bool ours = syn.is_object() && syn.size() == 2 && syn.contains("scene") && syn["scene"].is_string() &&
                      syn.contains("seed") && syn["seed"].is_number_unsigned() &&
                      syn["seed"].get<std::uint64_t>() <= 0xffffffffull;
    if (ours && !s.synthetic)
      s.synthetic = SensorInfo::Synthetic{syn["scene"].get<std::string>(), syn["seed"].get<std::uint32_t>()};
    else if (!ours)
      s.warnings.push_back(
          Say(syn.is_object() ? words::kForeignSyntheticKeys : words::kForeignSyntheticValue, {file.string()}));
  }
  return s;
}

void WriteSensorJson(const std::filesystem::path& file, const SensorInfo& s) {
  WriteFileAtomically(file, SensorToJson(s, file.string()).dump(2) + "\n");
}

void UpdateSensorJson(const std::filesystem::path& file, const SensorInfo& s) {
  json merged = SensorToJson(s, file.string());
  std::error_code ec;
  if (std::filesystem::is_regular_file(file, ec)) {
    json old;
    try {
      old = ReadJsonFile(file);
    } catch (const Error&) {
      old = nullptr;  // not JSON: replaced, as asked
    }
    if (old.is_object()) {
      json own_block = merged.contains("hdrfusion") ? merged["hdrfusion"] : json::object();
      for (auto it = merged.begin(); it != merged.end(); ++it)
        if (it.key() != "hdrfusion") old[it.key()] = it.value();
      if (!own_block.empty()) {
        if (!old.contains("hdrfusion") || !old["hdrfusion"].is_object()) old["hdrfusion"] = json::object();
        for (auto it = own_block.begin(); it != own_block.end(); ++it) old["hdrfusion"][it.key()] = it.value();
      }
      merged = std::move(old);
    }
  }
  WriteFileAtomically(file, merged.dump(2) + "\n");
}

json SensorToJson(const SensorInfo& s, const std::string& what) {
  const std::string& file = what;
  json j;
  j["camera"] = {{"width", s.camera.width}, {"height", s.camera.height}, {"fx", s.camera.fx},
                 {"fy", s.camera.fy},       {"cx", s.camera.cx},         {"cy", s.camera.cy}};
  j["depth"] = {{"scale", s.depth_scale}};
  if (s.response) {
    s.response->Check(file);
    const char* ch[3] = {"r", "g", "b"};
    json inv;
    for (int c = 0; c < 3; ++c)
      inv[ch[c]] = std::vector<float>(s.response->table[c].begin(), s.response->table[c].end());
    j["response"] = {{"inverse", inv}};
  }
  if (s.noise) {
    s.noise->Check(file);
    j["noise"] = {{"sigma_s", s.noise->sigma_s}, {"sigma_c", s.noise->sigma_c}};
  }
  if (s.synthetic) j["hdrfusion"]["synthetic"] = {{"scene", s.synthetic->scene}, {"seed", s.synthetic->seed}};
  if (s.device) {
    json dev = {{"serial", s.device->serial}};
    if (!s.device->name.empty()) dev["name"] = s.device->name;
    if (s.device->exposure_ms_per_unit) dev["exposure_ms_per_unit"] = *s.device->exposure_ms_per_unit;
    j["hdrfusion"]["device"] = dev;
  }
  return j;
}

}  // namespace hdrf::io
