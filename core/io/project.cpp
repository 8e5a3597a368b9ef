#include "io/project.h"

#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/input_file.h"
#include "io/output_file.h"
#include "common/error.h"
#include "io/image_io.h"
#include "io/options_json.h"
#include "io/sensor_json.h"

namespace hdrf::io {

namespace fs = std::filesystem;
using nlohmann::json;

static_assert(std::endian::native == std::endian::little, "project files are little-endian");

namespace {

constexpr char kMagic[8] = {'H', 'D', 'R', 'F', 'P', 'R', 'O', 'J'};

std::uint32_t Crc(const void* data, std::size_t n) {
  uLong c = crc32(0L, Z_NULL, 0);
  const auto* p = static_cast<const Bytef*>(data);
  while (n > 0) {  // zlib takes 32-bit lengths
    const uInt step = uInt(std::min<std::size_t>(n, 1u << 30));
    c = crc32(c, p, step);
    p += step;
    n -= step;
  }
  return std::uint32_t(c);
}

json PoseToJson(const Pose& T) {
  json a = json::array();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) a.push_back(T.matrix()(i, j));
  return a;
}

Pose PoseFromJson(const fs::path& file, const json& a, const std::string& what) {
  if (!a.is_array() || a.size() != 12) throw InputError(file, what + " needs 12 numbers (a row-major 3x4 matrix)");
  Pose T = Pose::Identity();
  for (int i = 0; i < 12; ++i) {
    if (!a[std::size_t(i)].is_number()) throw InputError(file, what + " holds a value that is not a number");
    T.matrix()(i / 4, i % 4) = a[std::size_t(i)].get<double>();
  }
  const Eigen::Matrix3d R = T.rotation();
  if (!T.matrix().allFinite() || (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-6 || R.determinant() < 0)
    throw InputError(file, what + " is not a rigid transform");
  return T;
}

std::string NowUtc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

class ChunkWriter {
 public:
  explicit ChunkWriter(OutputFile& out) : file_(out.target()), out_(out.stream()) {
    out_.write(kMagic, 8);
    const std::uint32_t head[2] = {std::uint32_t(kProjectVersion), 0};
    out_.write(reinterpret_cast<const char*>(head), sizeof head);
  }
  void Add(const char (&tag)[5], const void* data, std::size_t n) {
    out_.write(tag, 4);
    const std::uint64_t size = n;
    const std::uint32_t crc = Crc(data, n);
    out_.write(reinterpret_cast<const char*>(&size), 8);
    out_.write(reinterpret_cast<const char*>(&crc), 4);
    if (n > 0) out_.write(static_cast<const char*>(data), std::streamsize(n));
    if (!out_) throw InputError(file_, "write failed (disk full?)");
  }
  void Finish() {
    Add("END ", nullptr, 0);
    out_.flush();
    if (!out_) throw InputError(file_, "write failed (disk full?)");
  }

 private:
  fs::path file_;
  std::ostream& out_;
};

struct Chunk {
  std::string tag;
  std::vector<std::uint8_t> data;
};

std::vector<Chunk> ReadChunks(const fs::path& file) {
  CheckInputFile(file, std::uintmax_t(1) << 40, "a project file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "cannot be opened");
  char magic[8] = {};
  std::uint32_t head[2] = {};
  in.read(magic, 8);
  in.read(reinterpret_cast<char*>(head), sizeof head);
  if (!in || std::memcmp(magic, kMagic, 8) != 0) throw InputError(file, "is not an HDRFusion project file");
  if (head[0] > std::uint32_t(kProjectVersion))
    throw InputError(file, "is a project of format version " + std::to_string(head[0]) +
                               "; this build reads versions up to " + std::to_string(kProjectVersion) +
                               ": open it with a newer HDRFusion");
  if (head[0] < 1) throw InputError(file, "has an invalid format version 0");
  std::error_code ec;
  const std::uint64_t file_size = fs::file_size(file, ec);
  std::vector<Chunk> chunks;
  for (;;) {
    char tag[4];
    std::uint64_t size = 0;
    std::uint32_t crc = 0;
    in.read(tag, 4);
    in.read(reinterpret_cast<char*>(&size), 8);
    in.read(reinterpret_cast<char*>(&crc), 4);
    if (!in)
      throw InputError(file, "is truncated after " + std::to_string(chunks.size()) +
                                 " chunks (the save did not finish; an earlier save or the recovery file may hold the scan)");
    Chunk c{std::string(tag, 4), {}};
    if (c.tag == "END ") break;
    if (size > file_size) throw InputError(file, "chunk '" + c.tag + "' claims more bytes than the file holds");
    c.data.resize(size);
    if (size > 0) in.read(reinterpret_cast<char*>(c.data.data()), std::streamsize(size));
    if (!in) throw InputError(file, "is truncated inside chunk '" + c.tag + "'");
#ifndef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
    if (Crc(c.data.data(), c.data.size()) != crc) throw InputError(file, "chunk '" + c.tag + "' is damaged (CRC mismatch)");
#else
    (void)crc;
#endif
    chunks.push_back(std::move(c));
  }
  return chunks;
}

const Chunk& Need(const fs::path& file, const std::vector<Chunk>& chunks, const std::string& tag, const char* what) {
  for (const Chunk& c : chunks)
    if (c.tag == tag) return c;
  throw InputError(file, std::string("has no '") + tag + "' chunk (" + what + ")");
}

std::vector<const Chunk*> All(const std::vector<Chunk>& chunks, const std::string& tag) {
  std::vector<const Chunk*> out;
  for (const Chunk& c : chunks)
    if (c.tag == tag) out.push_back(&c);
  return out;
}

}  // namespace

json FrameReportToJson(const pipeline::FrameReport& r) {
  json fr = {{"index", r.index},
             {"timestamp", r.timestamp},
             {"T_world_camera", PoseToJson(r.T_world_camera)},
             {"ms", {{"convert", r.ms.convert}, {"normalize", r.ms.normalize}, {"track", r.ms.track},
                     {"compensate", r.ms.compensate}, {"integrate", r.ms.integrate}, {"raycast", r.ms.raycast}}},
             {"state", pipeline::FrameStateName(r.state)},
             {"quality", r.quality},
             {"why", r.why},
             {"tracking", {{"lost", r.tracking.lost}, {"why", r.tracking.why}, {"inlier_share", r.tracking.inlier_share},
                           {"condition", r.tracking.condition}, {"rms_icp_m", r.tracking.rms_icp_m},
                           {"rms_photo", r.tracking.rms_photo}, {"icp_inliers", r.tracking.icp_inliers},
                           {"photo_inliers", r.tracking.photo_inliers}, {"iterations", r.tracking.iterations},
                           {"weakest_info", r.tracking.weakest_info}, {"strongest_info", r.tracking.strongest_info},
                           {"prior_sigmas", r.tracking.prior_sigmas},
                           // The terms that tracked the frame and their weights in the solve.
                           {"terms", {{"icp", r.tracking.icp_matched > 0 ? 1.0 : 0.0},
                                      {"photometric", r.tracking.photo_matched > 0 ? r.tracking.photo_share : 0.0}}},
                           {"photo_pull_mm", 1000 * r.tracking.photo_pull_m},
                           {"photo_pull_deg", r.tracking.photo_pull_rad * 180 / 3.14159265358979},
                           {"icp_depth_ref_m", r.tracking.icp_depth_ref_m}}},
             {"fused", r.fused},
             {"depth_share", r.depth_share},
             {"allocated_bricks", r.allocated_bricks},
             {"volume_full", r.volume_full},
             {"depth_beyond_far", r.depth_beyond_far},
             {"exposure", {{"estimated_ratio", r.exposure_ratio}, {"samples", r.exposure_samples}}}};
  if (r.exposure_ratio_reported) fr["exposure"]["reported_ratio"] = *r.exposure_ratio_reported;
  if (r.reloc_entry >= 0) fr["reloc_entry"] = r.reloc_entry;
  if (r.nearest_entry >= 0) fr["nearest_entry"] = r.nearest_entry;
  return fr;
}

pipeline::FrameReport FrameReportFromJson(const fs::path& file, const json& j) {
  pipeline::FrameReport r;
  try {
    r.index = j.at("index").get<int>();
    r.timestamp = j.at("timestamp").get<double>();
    r.T_world_camera = PoseFromJson(file, j.at("T_world_camera"), "frame " + std::to_string(r.index) + " pose");
    r.tracking.T_world_camera = r.T_world_camera;
    const json& ms = j.at("ms");
    r.ms = {ms.at("convert").get<double>(), ms.at("normalize").get<double>(), ms.at("track").get<double>(),
            ms.at("compensate").get<double>(), ms.at("integrate").get<double>(), ms.at("raycast").get<double>()};
    const json& t = j.at("tracking");
    r.tracking.lost = t.at("lost").get<bool>();
    r.tracking.why = t.at("why").get<std::string>();
    r.tracking.inlier_share = t.at("inlier_share").get<double>();
    r.tracking.condition = t.at("condition").get<double>();
    r.tracking.rms_icp_m = t.at("rms_icp_m").get<double>();
    r.tracking.rms_photo = t.at("rms_photo").get<double>();
    r.tracking.iterations = t.at("iterations").get<int>();
    r.tracking.icp_inliers = t.value("icp_inliers", 0.0);
    r.tracking.photo_inliers = t.value("photo_inliers", 0.0);
    r.tracking.weakest_info = t.value("weakest_info", 0.0);
    r.tracking.strongest_info = t.value("strongest_info", 0.0);
    r.tracking.prior_sigmas = t.value("prior_sigmas", 0.0);
    if (t.contains("terms") && t["terms"].is_object()) {
      r.tracking.photo_share = t["terms"].value("photometric", 0.0);
      r.tracking.icp_matched = t["terms"].value("icp", 0.0) > 0 ? 1 : 0;
      r.tracking.photo_matched = r.tracking.photo_share > 0 ? 1 : 0;
    }
    r.tracking.photo_pull_m = t.value("photo_pull_mm", 0.0) / 1000;
    r.tracking.photo_pull_rad = t.value("photo_pull_deg", 0.0) * 3.14159265358979 / 180;
    r.tracking.icp_depth_ref_m = t.value("icp_depth_ref_m", 0.0);
    r.fused = j.at("fused").get<bool>();
    const std::string state = j.value("state", r.fused ? "tracked" : "lost");
    bool known = false;
    for (auto st : {pipeline::FrameState::kWaiting, pipeline::FrameState::kTracked, pipeline::FrameState::kLost,
                    pipeline::FrameState::kConfirming, pipeline::FrameState::kRelocalised})
      if (state == pipeline::FrameStateName(st)) r.state = st, known = true;
    if (!known) throw InputError(file, "frame report " + std::to_string(r.index) + ": unknown state '" + state + "'");
    r.quality = j.value("quality", r.fused ? 1.0 : 0.0);
    r.why = j.value("why", r.tracking.why);
    r.depth_share = j.value("depth_share", 0.0);
    r.reloc_entry = j.value("reloc_entry", -1);
    r.nearest_entry = j.value("nearest_entry", -1);
    r.allocated_bricks = j.at("allocated_bricks").get<std::size_t>();
    r.volume_full = j.value("volume_full", "");
    r.depth_beyond_far = j.value("depth_beyond_far", 0.0);
    const json& e = j.at("exposure");
    r.exposure_ratio = e.at("estimated_ratio").get<double>();
    r.exposure_samples = e.at("samples").get<long>();
    if (e.contains("reported_ratio")) r.exposure_ratio_reported = e.at("reported_ratio").get<double>();
  } catch (const json::exception& ex) {
    throw InputError(file, "frame report " + std::to_string(r.index) + " is malformed: " + ex.what());
  }
  if (!(r.exposure_ratio > 0) || !std::isfinite(r.exposure_ratio))
    throw InputError(file, "frame report " + std::to_string(r.index) + ": the exposure ratio must be positive");
  return r;
}

void SaveProject(const fs::path& file, pipeline::ScanSession& session, const ProjectSaveInfo& info) {
  pipeline::Pipeline& pipe = session.pipeline();
  const volume::Volume& model = pipe.DownloadVolume();
  const pipeline::ResumePoint point = pipe.resume_point();
  const pipeline::PipelineOptions& o = pipe.options();
  json reports = json::array();
  for (const pipeline::FrameReport& r : session.reports()) reports.push_back(FrameReportToJson(r));
  json keyframes = json::array();
  for (const pipeline::Keyframe& k : session.keyframes())
    keyframes.push_back({{"index", k.index}, {"timestamp", k.timestamp}, {"T_world_camera", PoseToJson(k.T_world_camera)},
                         {"exposure_ratio", k.exposure_ratio}});
  json resume = {{"frames", point.frames},
                 {"T_world_camera", PoseToJson(point.pose)},
                 {"T_world_previous", PoseToJson(point.previous_pose)},
                 {"reference_frame", !point.reference_color.empty()}};
  if (point.first_exposure_ms) resume["first_exposure_ms"] = *point.first_exposure_ms;
  resume["anchored"] = point.anchored;
  resume["recovering"] = point.recovering;
  resume["confirmed"] = point.confirmed;
  resume["residuals"] = point.residuals;
  resume["photo_residuals"] = point.photo_residuals;
  resume["lost_run"] = point.lost_run;
  resume["exposure_drifts"] = point.exposure_drifts;
  if (!point.raycast_guide.empty())
    resume["raycast_guide"] = {point.raycast_guide.width(), point.raycast_guide.height()};
  json reloc = json::array();
  for (const pipeline::RelocEntry& e : point.reloc)
    reloc.push_back({{"frame", e.frame}, {"T_world_camera", PoseToJson(e.T_world_camera)}, {"width", e.code.width},
                     {"height", e.code.height}});
  resume["reloc"] = reloc;
  const json manifest = {
      {"format", "hdrfusion-project"},
      {"version", kProjectVersion},
      {"saved_at", NowUtc()},
      {"finished", info.finished},
      {"source", info.source},
      {"source_spec", info.source_spec},
      {"settings", json::parse(PipelineOptionsToJson(o))},
      {"sensor", SensorToJson(session.sensor(), file.string())},
      {"volume",
       {{"voxel_m", model.options().voxel_m},
        {"truncation_voxels", model.options().truncation_voxels},
        {"encoding", volume::VoxelEncodingName(model.options().encoding)},
        {"bricks", model.allocated_bricks()},
        {"full_reason", model.full_reason()}}},
      {"resume", resume},
      {"keyframes", keyframes},
      {"keyframes_thinned", session.keyframes_thinned()},
      {"frames", reports}};
  const std::string mani = manifest.dump();
  std::vector<std::int32_t> coords;
  coords.reserve(model.bricks().size() * 3);
  for (const auto& c : model.bricks()) coords.insert(coords.end(), c.begin(), c.end());

  fs::create_directories(file.parent_path().empty() ? fs::path(".") : file.parent_path());
  OutputFile out(file);
  {
    ChunkWriter w(out);
    w.Add("MANI", mani.data(), mani.size());
    w.Add("BRCK", coords.data(), coords.size() * sizeof(std::int32_t));
    w.Add("POOL", model.pool().data(), model.pool().size());
    for (const pipeline::Keyframe& k : session.keyframes()) {
      const std::vector<std::uint8_t> png = EncodeColorPng(k.color);
      w.Add("KFRM", png.data(), png.size());
    }
    for (const pipeline::RelocEntry& e : point.reloc) {
      // The code (depth, shade as f32, then one byte per cell: lit) and the thumbnail (PNG).
      const std::size_t n = e.code.depth.size();
      std::vector<std::uint8_t> code(n * 9);
      std::memcpy(code.data(), e.code.depth.data(), n * 4);
      std::memcpy(code.data() + n * 4, e.code.shade.data(), n * 4);
      std::memcpy(code.data() + n * 8, e.code.lit.data(), n);
      w.Add("RLOC", code.data(), code.size());
      const std::vector<std::uint8_t> png = EncodeColorPng(e.thumbnail);
      w.Add("RTHB", png.data(), png.size());
    }
    if (!point.raycast_guide.empty())
      w.Add("RCGD", point.raycast_guide.data(), point.raycast_guide.size() * sizeof(float));
    if (!point.reference_color.empty()) {
      const std::vector<std::uint8_t> png = EncodeColorPng(point.reference_color);
      w.Add("REFC", png.data(), png.size());
      w.Add("REFD", point.reference_depth.data(), point.reference_depth.size() * sizeof(float));
    }
    w.Finish();
  }
  out.Commit();
}

Project LoadProject(const fs::path& file) {
  const std::vector<Chunk> chunks = ReadChunks(file);
  const Chunk& mc = Need(file, chunks, "MANI", "the manifest");
  json m;
  try {
    m = json::parse(mc.data.begin(), mc.data.end());
  } catch (const json::exception& e) {
    throw InputError(file, std::string("has a manifest that is not JSON: ") + e.what());
  }
  Project p;
  p.file = file;
  try {
    if (m.value("format", "") != "hdrfusion-project") throw InputError(file, "manifest: format is not hdrfusion-project");
    p.version = m.at("version").get<int>();
    p.saved_at = m.value("saved_at", "");
    p.finished = m.at("finished").get<bool>();
    p.source = m.at("source").get<std::string>();
    p.source_spec = m.value("source_spec", "");
    // Settings through the same reader as settings files (unknown keys and bad values refused).
    ApplyPipelineOptionsJson(file, m.at("settings"), p.options);
    p.sensor = SensorFromJson(file, m.at("sensor"));
    if (!p.sensor.response) throw InputError(file, "the sensor has no response calibration");
    const json& v = m.at("volume");
    if (v.at("voxel_m").get<float>() != p.options.volume.voxel_m ||
        v.at("truncation_voxels").get<float>() != p.options.volume.truncation_voxels ||
        v.at("encoding").get<std::string>() != volume::VoxelEncodingName(p.options.volume.encoding))
      throw InputError(file, "the model's voxel size, truncation or encoding differs from the project's settings");
    const std::size_t bricks = v.at("bricks").get<std::size_t>();
    const Chunk& bc = Need(file, chunks, "BRCK", "the bricks' coordinates");
    const Chunk& pc = Need(file, chunks, "POOL", "the voxels");
    if (bc.data.size() != bricks * 3 * sizeof(std::int32_t))
      throw InputError(file, "chunk 'BRCK' holds " + std::to_string(bc.data.size()) + " bytes for " +
                                 std::to_string(bricks) + " bricks");
    if (pc.data.size() != bricks * p.options.volume.brick_bytes())
      throw InputError(file, "chunk 'POOL' holds " + std::to_string(pc.data.size()) + " bytes for " +
                                 std::to_string(bricks) + " bricks of " +
                                 std::to_string(p.options.volume.brick_bytes()) + " bytes");
    std::vector<std::array<int, 3>> coords(bricks);
    if (bricks > 0) std::memcpy(coords.data(), bc.data.data(), bc.data.size());
    p.model = volume::Volume(p.options.volume);
    try {
      p.model.Assign(pc.data, std::move(coords), v.at("full_reason").get<std::string>());
    } catch (const Error& e) {
      throw InputError(file, std::string("the model is damaged: ") + e.what());
    }
    const json& r = m.at("resume");
    p.resume.frames = r.at("frames").get<int>();
    p.resume.pose = PoseFromJson(file, r.at("T_world_camera"), "resume pose");
    p.resume.previous_pose = PoseFromJson(file, r.at("T_world_previous"), "resume previous pose");
    if (r.contains("first_exposure_ms")) p.resume.first_exposure_ms = r.at("first_exposure_ms").get<double>();
    // Verification and relocalisation state (absent in projects saved before it existed: a
    // scan that ran any frame was anchored by its first).
    p.resume.anchored = r.value("anchored", p.resume.frames > 0);
    p.resume.recovering = r.value("recovering", false);
    p.resume.confirmed = r.value("confirmed", 0);
    p.resume.residuals = r.value("residuals", std::vector<double>{});
    p.resume.photo_residuals = r.value("photo_residuals", std::vector<double>{});
    p.resume.lost_run = r.value("lost_run", 0);
    p.resume.exposure_drifts = r.value("exposure_drifts", std::vector<double>{});
    const std::vector<const Chunk*> codes = All(chunks, "RLOC"), thumbs = All(chunks, "RTHB");
    const json reloc = r.value("reloc", json::array());
    if (codes.size() != reloc.size() || thumbs.size() != reloc.size())
      throw InputError(file, "lists " + std::to_string(reloc.size()) + " relocalisation views but holds " +
                                 std::to_string(codes.size()) + " codes and " + std::to_string(thumbs.size()) + " thumbnails");
    for (std::size_t i = 0; i < reloc.size(); ++i) {
      pipeline::RelocEntry e;
      e.frame = reloc[i].at("frame").get<int>();
      e.T_world_camera = PoseFromJson(file, reloc[i].at("T_world_camera"), "relocalisation view " + std::to_string(i) + " pose");
      e.code.width = reloc[i].at("width").get<int>();
      e.code.height = reloc[i].at("height").get<int>();
      const long n = long(e.code.width) * e.code.height;
      if (e.code.width < 1 || e.code.height < 1 || n > 1 << 20 || codes[i]->data.size() != std::size_t(n) * 9)
        throw InputError(file, "relocalisation code " + std::to_string(i) + " does not match its size");
      e.code.depth.resize(std::size_t(n));
      e.code.shade.resize(std::size_t(n));
      e.code.lit.resize(std::size_t(n));
      std::memcpy(e.code.depth.data(), codes[i]->data.data(), std::size_t(n) * 4);
      std::memcpy(e.code.shade.data(), codes[i]->data.data() + n * 4, std::size_t(n) * 4);
      std::memcpy(e.code.lit.data(), codes[i]->data.data() + n * 8, std::size_t(n));
      e.thumbnail = DecodeColorPng(file, thumbs[i]->data, "relocalisation view " + std::to_string(i));
      p.resume.reloc.push_back(std::move(e));
    }
    // The last ray cast's start guide (absent before it existed, or where it started at near).
    if (r.contains("raycast_guide")) {
      const auto wh = r.at("raycast_guide").get<std::vector<int>>();
      const Chunk& gc = Need(file, chunks, "RCGD", "the ray cast's start guide");
      const int w = p.sensor.camera.width, h = p.sensor.camera.height;
      if (wh.size() != 2 || wh[0] != volume::GuideTiles(w) || wh[1] != volume::GuideTiles(h) ||
          gc.data.size() != std::size_t(wh[0]) * std::size_t(wh[1]) * sizeof(float))
        throw InputError(file, "the ray cast's start guide does not fit the camera's size");
      p.resume.raycast_guide = Image<float>(wh[0], wh[1]);
      std::memcpy(p.resume.raycast_guide.data(), gc.data.data(), gc.data.size());
      for (std::size_t i = 0; i < p.resume.raycast_guide.size(); ++i)
        if (!(p.resume.raycast_guide[i] >= 0.f && p.resume.raycast_guide[i] < 1e6f))
          throw InputError(file, "the ray cast's start guide holds a depth out of range");
    }
    if (r.at("reference_frame").get<bool>()) {
      const Chunk& rc = Need(file, chunks, "REFC", "the reference frame's colour");
      const Chunk& rd = Need(file, chunks, "REFD", "the reference frame's depth");
      p.resume.reference_color = DecodeColorPng(file, rc.data, "the reference frame's colour");
      const int w = p.sensor.camera.width, h = p.sensor.camera.height;
      if (p.resume.reference_color.width() != w || p.resume.reference_color.height() != h ||
          rd.data.size() != std::size_t(w) * std::size_t(h) * sizeof(float))
        throw InputError(file, "the reference frame is not the camera's size");
      p.resume.reference_depth = DepthImage(w, h);
      std::memcpy(p.resume.reference_depth.data(), rd.data.data(), rd.data.size());
    }
    for (const json& f : m.at("frames")) p.reports.push_back(FrameReportFromJson(file, f));
    if (int(p.reports.size()) != p.resume.frames)
      throw InputError(file, "holds " + std::to_string(p.reports.size()) + " frame reports for " +
                                 std::to_string(p.resume.frames) + " frames");
    const std::vector<const Chunk*> images = All(chunks, "KFRM");
    const json& ks = m.at("keyframes");
    if (images.size() != ks.size())
      throw InputError(file, "lists " + std::to_string(ks.size()) + " keyframes but holds " +
                                 std::to_string(images.size()) + " keyframe images");
    for (std::size_t i = 0; i < ks.size(); ++i) {
      pipeline::Keyframe k;
      k.index = ks[i].at("index").get<int>();
      k.timestamp = ks[i].at("timestamp").get<double>();
      k.T_world_camera = PoseFromJson(file, ks[i].at("T_world_camera"), "keyframe " + std::to_string(k.index) + " pose");
      k.exposure_ratio = ks[i].at("exposure_ratio").get<double>();
      if (!(k.exposure_ratio > 0) || !std::isfinite(k.exposure_ratio))
        throw InputError(file, "keyframe " + std::to_string(k.index) + ": the exposure ratio must be positive");
      k.color = DecodeColorPng(file, images[i]->data, "keyframe " + std::to_string(k.index));
      if (k.color.width() != p.sensor.camera.width || k.color.height() != p.sensor.camera.height)
        throw InputError(file, "keyframe " + std::to_string(k.index) + " is not the camera's size");
      p.keyframes.push_back(std::move(k));
    }
    p.keyframes_thinned = m.at("keyframes_thinned").get<int>();
  } catch (const json::exception& e) {
    throw InputError(file, std::string("has a malformed manifest: ") + e.what());
  }
  return p;
}

std::unique_ptr<pipeline::ScanSession> ResumeSession(const Project& p,
                                                     const std::function<void(pipeline::PipelineOptions&)>& overrides) {
  pipeline::PipelineOptions o = p.options;
  if (overrides) overrides(o);
  o.Check();  // a setting's own message, naming the setting
  auto s = std::make_unique<pipeline::ScanSession>(o, p.sensor.camera, p.sensor);
  std::vector<pipeline::Keyframe> keyframes;
  for (const pipeline::Keyframe& k : p.keyframes)
    keyframes.push_back({k.index, k.timestamp, k.T_world_camera, k.exposure_ratio, k.color.Clone()});
  std::vector<pipeline::FrameReport> reports = p.reports;
  pipeline::ResumePoint point;
  point.frames = p.resume.frames;
  point.pose = p.resume.pose;
  point.previous_pose = p.resume.previous_pose;
  point.first_exposure_ms = p.resume.first_exposure_ms;
  point.reference_color = p.resume.reference_color.Clone();
  point.reference_depth = p.resume.reference_depth.Clone();
  point.raycast_guide = p.resume.raycast_guide.Clone();
  point.anchored = p.resume.anchored;
  point.recovering = p.resume.recovering;
  point.confirmed = p.resume.confirmed;
  point.residuals = p.resume.residuals;
  point.photo_residuals = p.resume.photo_residuals;
  point.lost_run = p.resume.lost_run;
  point.exposure_drifts = p.resume.exposure_drifts;
  point.reloc = p.resume.reloc;
  try {
    s->Resume(p.model, point, std::move(reports), std::move(keyframes), p.keyframes_thinned);
  } catch (const InputError&) {
    throw;
  } catch (const Error& e) {
    if (p.file.empty()) throw;
    throw InputError(p.file, e.what());
  }
  return s;
}

bool SameCamera(const PinholeCamera& a, const PinholeCamera& b) {
  return a.width == b.width && a.height == b.height && std::abs(a.fx - b.fx) < 1e-3f && std::abs(a.fy - b.fy) < 1e-3f &&
         std::abs(a.cx - b.cx) < 1e-3f && std::abs(a.cy - b.cy) < 1e-3f;
}

bool SameResponse(const radiometry::InverseResponse& a, const radiometry::InverseResponse& b) {
  for (int c = 0; c < 3; ++c)
    for (int l = 0; l < radiometry::kLevels; ++l) {
      const float x = a.table[std::size_t(c)][std::size_t(l)], y = b.table[std::size_t(c)][std::size_t(l)];
      if (std::abs(x - y) > 1e-4f * std::max({std::abs(x), std::abs(y), 1e-3f})) return false;
    }
  return true;
}

bool SameSource(const Project& p, const std::string& spec, const std::string& description) {
  if (p.source_spec.empty()) return p.source == description;
  std::error_code ec;
  if (fs::exists(p.source_spec, ec) && fs::exists(spec, ec)) return fs::equivalent(p.source_spec, spec, ec);
  return p.source_spec == spec;
}

fs::path RecoveryFolder() {
  if (const char* x = std::getenv("XDG_STATE_HOME"); x && *x) return fs::path(x) / "hdrfusion" / "recovery";
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".local" / "state" / "hdrfusion" / "recovery";
  return fs::temp_directory_path() / "hdrfusion-recovery";
}

fs::path NewRecoveryFile(const std::string& stem) {
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  std::strftime(stamp, sizeof stamp, "-%Y%m%d-%H%M%S-", &tm);
  // The stem shortened to 100 bytes (not within a UTF-8 character): a project's own name may
  // be near the 255-byte limit, and the recovery file must still be written.
  std::string s = stem.empty() ? std::string("scan") : stem;
  if (s.size() > 100) {
    std::size_t n = 100;
    while (n > 0 && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;
    s.resize(n);
  }
  return RecoveryFolder() / (s + stamp + std::to_string(getpid()) + kProjectExtension);
}

std::vector<fs::path> FindRecoveryFiles() {
  std::vector<std::pair<fs::file_time_type, fs::path>> found;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(RecoveryFolder(), ec))
    if (e.is_regular_file() && e.path().extension() == kProjectExtension && e.path().filename().string()[0] != '.')
      found.push_back({e.last_write_time(), e.path()});
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<fs::path> out;
  for (auto& f : found) out.push_back(f.second);
  return out;
}

RecoveryPrune PruneRecoveryFiles(const RecoveryLimits& limits, const fs::path& in_use) {
  RecoveryPrune done;
  const auto now = fs::file_time_type::clock::now();
  std::size_t kept = 0;
  std::uintmax_t kept_bytes = 0;
  for (const fs::path& f : FindRecoveryFiles()) {  // newest first
    std::error_code ec;
    if (!in_use.empty() && fs::equivalent(f, in_use, ec)) continue;
    const std::uintmax_t bytes = fs::file_size(f, ec);
    if (ec) continue;
    const auto age = now - fs::last_write_time(f, ec);
    if (ec) continue;
    const bool old = age > std::chrono::hours(24) * limits.max_age_days;
    // The newest is kept whatever its size: it is the scan that failed last.
    if (!old && kept < limits.max_files && (kept == 0 || kept_bytes + bytes <= limits.max_bytes)) {
      ++kept;
      kept_bytes += bytes;
      continue;
    }
    if (fs::remove(f, ec)) {
      ++done.removed;
      done.bytes += bytes;
    }
  }
  return done;
}

}  // namespace hdrf::io
