#include "io/options_json.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "io/json_file.h"

namespace hdrf::io {

using nlohmann::json;

namespace {

template <typename T>
void Get(const std::filesystem::path& file, const json& obj, const std::string& section,
         const char* key, T& out) {
  if (!obj.contains(key)) return;
  try {
    out = obj.at(key).get<T>();
  } catch (const json::exception&) {
    throw InputError(file, "'" + section + key + "' has the wrong type");
  }
}

void RefuseUnknown(const std::filesystem::path& file, const json& obj, const std::string& section,
                   std::initializer_list<const char*> known) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool ok = false;
    for (const char* k : known) ok |= it.key() == k;
    if (!ok) throw InputError(file, "unknown setting '" + section + it.key() + "'");
  }
}

}  // namespace

void ReadPipelineOptions(const std::filesystem::path& file, pipeline::PipelineOptions& o) {
  const json j = ReadJsonFile(file);
  if (!j.is_object()) throw InputError(file, "top level must be a JSON object");
  RefuseUnknown(file, j, "", {"volume", "tracker", "nr", "pcf", "bilateral", "device"});
  Get(file, j, "", "pcf", o.pcf);
  Get(file, j, "", "bilateral", o.bilateral);
  if (j.contains("device")) {
    std::string d;
    Get(file, j, "", "device", d);
    if (d != "cpu" && d != "cuda") throw InputError(file, "'device' must be \"cpu\" or \"cuda\"");
    o.device = d == "cuda" ? Device::kCuda : Device::kCpu;
  }
  if (j.contains("volume")) {
    const json& v = j["volume"];
    RefuseUnknown(file, v, "volume.", {"resolution", "size_m", "truncation_voxels", "max_weight",
                                       "max_radiance_weight", "tau0", "tau1_deg", "max_memory_mb", "voxel"});
    Get(file, v, "volume.", "resolution", o.volume.resolution);
    Get(file, v, "volume.", "size_m", o.volume.size_m);
    Get(file, v, "volume.", "truncation_voxels", o.volume.truncation_voxels);
    Get(file, v, "volume.", "max_weight", o.volume.max_weight);
    Get(file, v, "volume.", "max_radiance_weight", o.volume.max_radiance_weight);
    Get(file, v, "volume.", "tau0", o.volume.tau0);
    Get(file, v, "volume.", "tau1_deg", o.volume.tau1_deg);
    Get(file, v, "volume.", "max_memory_mb", o.volume.max_memory_mb);
    if (v.contains("voxel")) {
      std::string e;
      Get(file, v, "volume.", "voxel", e);
      try {
        o.volume.encoding = volume::ParseVoxelEncoding(e);
      } catch (const Error& err) {
        throw InputError(file, std::string("'volume.voxel': ") + err.what());
      }
    }
  }
  if (j.contains("tracker")) {
    const json& t = j["tracker"];
    RefuseUnknown(file, t, "tracker.", {"kind", "frame_to_model", "levels", "iterations", "icp_sigma_m",
                                        "photo_sigma", "huber_k", "icp_max_dist_m", "icp_max_angle_deg",
                                        "min_inlier_share", "max_condition", "max_jump_m", "max_jump_deg"});
    if (t.contains("kind")) {
      std::string k;
      Get(file, t, "tracker.", "kind", k);
      o.tracker.kind = tracking::ParseTrackerKind(k);
    }
    Get(file, t, "tracker.", "frame_to_model", o.tracker.frame_to_model);
    Get(file, t, "tracker.", "levels", o.tracker.levels);
    if (t.contains("iterations")) {
      std::vector<int> it;
      Get(file, t, "tracker.", "iterations", it);
      if (it.empty() || it.size() > 4) throw InputError(file, "'tracker.iterations' needs 1 to 4 numbers");
      for (std::size_t i = 0; i < it.size(); ++i) o.tracker.iterations[i] = it[i];
    }
    Get(file, t, "tracker.", "icp_sigma_m", o.tracker.icp_sigma_m);
    Get(file, t, "tracker.", "photo_sigma", o.tracker.photo_sigma);
    Get(file, t, "tracker.", "huber_k", o.tracker.huber_k);
    Get(file, t, "tracker.", "icp_max_dist_m", o.tracker.icp_max_dist_m);
    Get(file, t, "tracker.", "icp_max_angle_deg", o.tracker.icp_max_angle_deg);
    Get(file, t, "tracker.", "min_inlier_share", o.tracker.min_inlier_share);
    Get(file, t, "tracker.", "max_condition", o.tracker.max_condition);
    Get(file, t, "tracker.", "max_jump_m", o.tracker.max_jump_m);
    Get(file, t, "tracker.", "max_jump_deg", o.tracker.max_jump_deg);
  }
  if (j.contains("nr")) {
    const json& n = j["nr"];
    RefuseUnknown(file, n, "nr.", {"patch", "downsample", "min_std"});
    Get(file, n, "nr.", "patch", o.nr.patch);
    Get(file, n, "nr.", "downsample", o.nr.downsample);
    Get(file, n, "nr.", "min_std", o.nr.min_std);
  }
  try {
    o.Check();
  } catch (const Error& e) {
    throw InputError(file, e.what());
  }
}

std::string PipelineOptionsToJson(const pipeline::PipelineOptions& o) {
  json j;
  j["pcf"] = o.pcf;
  j["bilateral"] = o.bilateral;
  j["device"] = DeviceName(o.device);
  j["volume"] = {{"resolution", o.volume.resolution}, {"size_m", o.volume.size_m},
                 {"truncation_voxels", o.volume.truncation_voxels}, {"max_weight", o.volume.max_weight},
                 {"max_radiance_weight", o.volume.max_radiance_weight}, {"tau0", o.volume.tau0},
                 {"tau1_deg", o.volume.tau1_deg}, {"max_memory_mb", o.volume.max_memory_mb},
                 {"voxel", volume::VoxelEncodingName(o.volume.encoding)}};
  j["tracker"] = {{"kind", tracking::TrackerName(o.tracker.kind)},
                  {"frame_to_model", o.tracker.frame_to_model},
                  {"levels", o.tracker.levels},
                  {"iterations", std::vector<int>(o.tracker.iterations.begin(), o.tracker.iterations.begin() + o.tracker.levels)},
                  {"icp_sigma_m", o.tracker.icp_sigma_m},
                  {"photo_sigma", o.tracker.photo_sigma},
                  {"huber_k", o.tracker.huber_k},
                  {"icp_max_dist_m", o.tracker.icp_max_dist_m},
                  {"icp_max_angle_deg", o.tracker.icp_max_angle_deg},
                  {"min_inlier_share", o.tracker.min_inlier_share},
                  {"max_condition", o.tracker.max_condition},
                  {"max_jump_m", o.tracker.max_jump_m},
                  {"max_jump_deg", o.tracker.max_jump_deg}};
  j["nr"] = {{"patch", o.nr.patch}, {"downsample", o.nr.downsample}, {"min_std", o.nr.min_std}};
  return j.dump(2);
}

}  // namespace hdrf::io
