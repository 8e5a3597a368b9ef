// Project files (docs/formats.md, "Project files"): one scan saved to be reopened, exported
// or continued later in the same coordinates. One file, `NAME.hdrproj`: a header, then
// chunks, each with its size and a CRC-32, so that a truncated or damaged file is refused
// naming the chunk. Saving writes a temporary sibling and renames it over the file: a save
// that is interrupted (a crash, a kill, a full disk) leaves the previous save intact.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/keyframes.h"
#include "pipeline/options.h"
#include "pipeline/pipeline.h"
#include "pipeline/scan_session.h"
#include "radiometry/sensor.h"
#include "volume/volume.h"

namespace hdrf::io {

inline constexpr int kProjectVersion = 1;
inline constexpr const char* kProjectExtension = ".hdrproj";

struct Project {
  std::filesystem::path file;            // where it was read from (names it in errors)
  int version = kProjectVersion;
  std::string source;                    // the source the scan read, as it described itself
  std::string source_spec;               // ... and as it was opened (`scan SOURCE`), if known
  std::string saved_at;                  // UTC, ISO 8601
  bool finished = false;                 // false: an autosave of a scan still running
  pipeline::PipelineOptions options;
  SensorInfo sensor;
  volume::Volume model{volume::VolumeOptions{}};
  pipeline::ResumePoint resume;
  std::vector<pipeline::FrameReport> reports;  // one per frame: pose, tracking, exposure, times
  std::vector<pipeline::Keyframe> keyframes;
  int keyframes_thinned = 0;
  int pcf_power() const { return options.pcf; }
};

struct ProjectSaveInfo {
  std::string source;       // the source's description
  std::string source_spec;  // what it was opened from ("" if not to be reopened)
  bool finished = false;
};

// Saves the session (the model downloaded from wherever it lives). Throws InputError naming
// the file where it cannot be written; the previous file is then untouched.
void SaveProject(const std::filesystem::path& file, pipeline::ScanSession& session, const ProjectSaveInfo& info);

// Reads a project; throws InputError naming the file and what is wrong (not a project, a
// newer version, a damaged or missing chunk, a model that does not fit its settings).
Project LoadProject(const std::filesystem::path& file);

// A session that goes on from the project: its settings (with `overrides` applied on top,
// which may not change the model's voxel size, truncation or encoding) and its camera.
// Throws InputError naming the project's file where they do not fit.
std::unique_ptr<pipeline::ScanSession> ResumeSession(const Project& project,
                                                     const std::function<void(pipeline::PipelineOptions&)>& overrides = {});

// Whether a source opened from `spec` (as described by `description`) is the one the project
// was scanned from, so that resuming goes on after its frames: the same folder or file
// (however the path is written), or the same synthetic or camera spec; projects that did not
// record their spec compare descriptions.
bool SameSource(const Project& project, const std::string& spec, const std::string& description);
// Whether a source's camera is the project's (size and intrinsics): a scan goes on only with
// the camera it began with.
bool SameCamera(const PinholeCamera& a, const PinholeCamera& b);
// Whether two responses are the same curve (every level within 1e-4 relatively): the model's
// radiance is in the units of the response it was scanned with, and frames converted
// through another would be fused as if they were the same light.
bool SameResponse(const radiometry::InverseResponse& a, const radiometry::InverseResponse& b);

// Recovery files: where autosaves of unfinished scans go (XDG state home,
// $XDG_STATE_HOME/hdrfusion/recovery, else ~/.local/state/hdrfusion/recovery), and the ones
// a crash left there, newest first.
std::filesystem::path RecoveryFolder();
// A fresh recovery file for a scan starting now: STEM-YYYYmmdd-HHMMSS-PID.hdrproj.
std::filesystem::path NewRecoveryFile(const std::string& stem);
std::vector<std::filesystem::path> FindRecoveryFiles();
// Recovery files are kept for a while, not for ever (every failed scan leaves one): the
// newest are kept up to these limits (the newest whatever its size), older ones and those
// beyond them are removed; `in_use` (a recovery file being resumed) never is.
struct RecoveryLimits {
  int max_age_days = 30;
  std::size_t max_files = 20;
  std::uintmax_t max_bytes = std::uintmax_t(4) << 30;  // 4 GiB
};
struct RecoveryPrune {
  int removed = 0;
  std::uintmax_t bytes = 0;
};
RecoveryPrune PruneRecoveryFiles(const RecoveryLimits& limits = {}, const std::filesystem::path& in_use = {});

// The per-frame report as stored in report.json and project files, and back.
nlohmann::json FrameReportToJson(const pipeline::FrameReport& r);
pipeline::FrameReport FrameReportFromJson(const std::filesystem::path& file, const nlohmann::json& j);

}  // namespace hdrf::io
