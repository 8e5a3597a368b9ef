// The scan job: one scan from its first frame to its outputs, as `hdrfusion scan` and the
// studio both run it. It holds the scan's session and its safety net: the recovery file the
// scan is autosaved to while it runs (io/project.h), the project it is saved as, and the
// output set a finished scan writes (trajectory, mesh, renders, keyframes, report) — all
// replaced together or not at all. Where the frames come from (a sequence, the synthetic
// sensor, a live camera the studio previews and reconnects) stays with the caller, which
// hands each frame to Process().
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "io/project.h"
#include "pipeline/frame_source.h"
#include "pipeline/scan_session.h"
#include "tonemap/operator.h"

namespace hdrf::jobs {

// Where a continued scan's source goes on from (ScanJob::Continue).
enum class ContinueFrom {
  kAfterScanned,  // the project's own bounded source, positioned after the frames scanned
  kFirstFrame,    // another (or a live) source, from its first frame: where the scan stopped
  kNothingLeft,   // the project's own source has no frames beyond those already scanned
  kOtherCamera,   // the source's camera is not the one the scan began with: it cannot go on
  kOtherResponse, // the source's response is not the one the scan began with: it cannot go on
};

// What WriteOutputs wrote.
struct OutputSummary {
  std::size_t vertices = 0, triangles = 0;
};

class ScanJob {
 public:
  // A new scan with `options` for a source with `sensor`. Autosaves go to a fresh recovery
  // file named after `name` (io::NewRecoveryFile) every `autosave_s` seconds (0: never).
  ScanJob(const pipeline::PipelineOptions& options, const SensorInfo& sensor, const std::string& name,
          double autosave_s);
  // A saved scan continued (io::LoadProject) with its settings, changed by `adjust` where
  // given (io::ResumeSession: throws InputError naming the project where they do not fit).
  ScanJob(const io::Project& project, const std::function<void(pipeline::PipelineOptions&)>& adjust,
          const std::string& name, double autosave_s);

  // The source the frames come from, as the project will name it and reopen it.
  void SetSource(const std::string& description, const std::string& spec);
  // A continued scan (made from `project`): `source`, opened from `spec`, positioned to go
  // on where the project's scan stopped. Where it is the project's own source, the project
  // goes on naming it as it did.
  ContinueFrom Continue(const io::Project& project, pipeline::FrameSource& source, const std::string& spec);
  // The continued project's frames and whether `source` is the one it was scanned from (so
  // that it goes on after those frames); 0 and false for a new scan.
  int continued_frames() const { return continued_frames_; }
  bool same_source() const { return same_source_; }

  // One frame through the engine.
  const pipeline::FrameReport& Process(const pipeline::FrameInput& frame) { return session_->Process(frame); }
  // The scan to its recovery file, when the autosave interval has passed (`force`: now), if
  // frames were added since the last save. Returns why it failed ("" where it saved or had
  // nothing to do); the scan goes on either way.
  std::string Autosave(bool force = false);
  // The scan saved as a project at `file` (finished: the scan ended there); the recovery file
  // is no longer needed. Throws InputError naming the file.
  void Save(const std::filesystem::path& file, bool finished);
  // The model kept in the recovery file, for a scan whose outputs cannot be written: a
  // sentence saying where it is and how to go on, or why it could not be kept.
  std::string Keep();
  // Before the program leaves: a scan with frames its user has not saved is autosaved one
  // last time (its recovery file is offered on the next start); a saved one leaves none.
  void Close();
  void DropRecovery();

  // The outputs a scan of `source_spec` writes into `out` and `project`, refused before the
  // scan where one may not be replaced (a link, a device, a folder) or where they are the
  // recording the scan reads (its sensor.json, say, replaced by the one the scan assumed):
  // checked by the caller before the first frame. Throws InputError naming the path.
  static void CheckOutputs(const std::filesystem::path& out, const std::filesystem::path& project,
                           const std::string& source_spec);
  // The finished scan's outputs as one set: the project at `project`, then `out`'s trajectory,
  // keyframes, mesh (display colours through `tone`), first and last renders and
  // report.json (`loop_s`: the loop's wall time, reading included), moved into place only
  // when every one is complete. On failure nothing in `out` changes and the model is kept in
  // the recovery file (the error says where). On success the recovery file is removed.
  // `say` hears what is being written, for the user. `cancelled` returning true stops the
  // writing between two outputs (and the mesh extraction within): Cancelled is thrown, whose
  // message says that nothing in `out` changed and where the model is kept.
  OutputSummary WriteOutputs(const std::filesystem::path& out, const std::filesystem::path& project,
                             const tonemap::OperatorDecl& tone, const tonemap::Params& tone_params, double loop_s,
                             const std::function<void(const std::string&)>& say = {},
                             const std::function<bool()>& cancelled = {});

  // What the job did on its own that the user should hear of (recovery files of old scans
  // removed to keep their folder bounded, io::PruneRecoveryFiles); empty if nothing.
  const std::string& notice() const { return notice_; }

  pipeline::ScanSession& session() { return *session_; }
  const pipeline::ScanSession& session() const { return *session_; }
  const std::filesystem::path& recovery_file() const { return recovery_; }

 private:
  io::ProjectSaveInfo Info(bool finished) const { return {source_, spec_, finished}; }
  void SaveRecovery();  // the scan as it stands to the recovery file (throws where it cannot)
  std::unique_ptr<pipeline::ScanSession> session_;
  std::filesystem::path recovery_;
  double autosave_s_ = 0;
  std::chrono::steady_clock::time_point autosave_time_;
  int saved_frames_ = 0;    // frames in the last save or autosave
  int saved_by_user_ = 0;   // frames in the last save the user asked for (or the project opened)
  std::string source_, spec_;
  std::string notice_;
  void Prune(const std::filesystem::path& in_use);
  int continued_frames_ = 0;
  bool same_source_ = false;
};

}  // namespace hdrf::jobs
