// The pipeline on its own thread. The worker owns the frame source and the pipeline, runs
// frames while scanning, and publishes each result as an immutable snapshot (shared
// pointer): views take the latest and drop what they had no time for, so a slow view never
// stalls the scan. Errors from the source or the engine pause the scan with a message; the
// model built so far is kept.
//
// Every command reaches the worker as a queued call on its thread (the thread's event queue
// is the command queue): they run between two frames, never during one. With a live camera
// (an "openni:..." source) the worker also previews while it is not scanning, applies the
// camera's exposure controls, records, and survives an unplug: the scan pauses with its model,
// and resumes when the same camera (same serial) comes back.
#pragma once

#include "gui/export_dialog.h"
#include "gui/shared_series.h"
#include "io/asset_export.h"

#include <QImage>
#include <QObject>
#include <QThread>
#include <array>
#include <atomic>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "jobs/scan_job.h"
#include "mesh/incremental_mesh.h"
#include "mesh/mesh.h"
#include "pipeline/frame_source.h"
#include "pipeline/scan_session.h"
#include "sensors/live_source.h"
#include "sensors/recorder.h"

namespace hdrf::gui {

struct ScanSettings {
  std::string source = "synthetic:scene=room,frames=300,ae=flicker";  // as `hdrfusion scan` takes it
  pipeline::PipelineOptions pipeline;
  // Refresh of the 3-D view's mesh, on the mesher's own thread from the bricks changed since
  // the last refresh: at most every this many frames, no more often than mesh_min_interval_ms,
  // and never while the last refresh is still being meshed.
  int mesh_every_frames = 1;
  int mesh_min_interval_ms = 400;
  // The stage images a snapshot carries (only those of views on screen, ScanWorker::
  // SetShownViews) are copied at most this often (0: every frame), or at the window's rate
  // where it asks for less (ScanWorker::SetImagesIntervalMs). The first and the last frame of
  // a scan always carry them.
  int images_min_interval_ms = 40;
  // Autosave of the scan to a recovery file (io/project.h) while scanning: every this many
  // seconds (0: never).
  double autosave_s = 60;
};

// A live camera's state, as the sensor panel shows it.
struct LiveStatus {
  sensors::DeviceEntry device;
  sensors::ExposureState exposure;
  bool has_camera_settings = false;
  std::optional<double> ms_per_unit;  // the profile's exposure unit (none: raw units only)
  bool own_profile = false;
  long dropped = 0;                   // frames the camera numbered that never arrived
  double fps = 0;                     // frames read per second (recent)
  bool recording = false;
  std::string recording_path;
  sensors::RecordingStats recording_stats;
};

// A device as the sensor list shows it.
struct SensorListing {
  sensors::DeviceEntry entry;
  bool own_profile = false;  // a calibration for this serial is stored
  bool in_use = false;       // the studio has it open
};

// The surface meshed off the scan's thread (mesh/incremental_mesh.h): the bricks that changed
// come in, the whole surface goes out (meshReady). Lives on its own thread, below the scan's
// priority.
class MeshWorker : public QObject {
  Q_OBJECT
 public:
  std::atomic<bool> busy{false};  // a refresh queued or being meshed
  // Both run on the mesher's thread (queued calls).
  void Reset(const volume::VolumeOptions& o);
  // `generation`: the model the bricks came from (ScanWorker counts them), sent back with the
  // surface so that one meshed from a model since dropped is not shown.
  // `step`: the surface's detail (mesh::IncrementalMesher: 1 every voxel, 2 or 4 a coarser
  // preview); `refresh_after`: its bricks' refresh (IncrementalMesher::Apply).
  void Apply(const std::shared_ptr<const volume::BrickSet>& changed, bool last, int generation, int step,
             int refresh_after);
 signals:
  void meshReady(std::shared_ptr<const hdrf::mesh::Mesh> mesh, bool last, int generation);

 private:
  std::unique_ptr<mesh::IncrementalMesher> mesher_;
};

// What one processed frame leaves for the views (all host copies, never modified).
struct Snapshot {
  bool preview = false;              // a live frame shown, not scanned (colour and depth only)
  std::optional<LiveStatus> live;
  pipeline::FrameReport report;
  ColorImage color;
  // While lost: the earlier view of the scan this frame looks most like (where to point the
  // camera), and the frame it was taken at; empty otherwise.
  ColorImage reloc_hint;
  int reloc_hint_frame = -1;
  pipeline::FrameViews images;       // radiance, confidence, filtered depth, NR, ray cast (those
                                     // shown, at the display's rate: may be empty)
  bool has_images = false;           // `images` were taken with this frame (at the display's rate)
  PinholeCamera camera;
  // Every pose so far, and the exposure ratios per frame (reported: NaN if none): prefixes of
  // series the scan shares with every snapshot (shared_series.h), not copies.
  SharedSeries<Pose>::Prefix trajectory;
  SharedSeries<double>::Prefix exposure_estimated, exposure_reported;
  std::shared_ptr<const mesh::Mesh> mesh;  // latest meshed surface (may be older than the frame)
  std::size_t volume_bytes = 0, bricks = 0;
  double volume_budget_mb = 0;       // volume.max_memory_mb
  double gpu_budget_mb = 0;          // volume.gpu_memory_mb (0: none)
  pipeline::StreamingStats streaming;  // bricks on the GPU and in host memory
  std::string volume_full;           // why the volume stopped growing ("" while it grows)
  std::array<Float3, 2> volume_bounds{};  // the allocated region (world box)
  double raycast_far_m = 0;          // the ray cast's reach (volume.raycast_far_m)
  int frames_total = -1;             // of the source (-1: unbounded)
  std::string device;                // "cpu" or "cuda"
};

class ScanWorker : public QObject {
  Q_OBJECT
 public:
  ScanWorker();
  ~ScanWorker() override;
  // How often the window takes the stage images while a scan runs (any thread; 0: as the
  // settings say): snapshots in between carry none, so the scan copies no image no one sees.
  void SetImagesIntervalMs(int ms) { images_interval_ms_ = ms; }
  bool running() const { return running_; }
  // Cancels an export in progress (any thread).
  void CancelExport() { cancel_export_ = true; }
  // The stage images the window shows now (any thread): snapshots carry only those.
  void SetShownViews(const pipeline::ViewSet& v);
  pipeline::ViewSet ShownViews() const;
  // The surface's lattice while a scan runs (any thread): 1 every voxel, 2 every other (a
  // quarter of the triangles), 4 every fourth (a sixteenth: for a display that cannot redraw
  // more than that twice a second, gui::PreviewDetail). In a preview, a brick whose surface is
  // shown is re-meshed at most every kPreviewRefresh refreshes; one without surface yet at once. When the scan stops, pauses or finishes the
  // whole surface (every voxel) follows either way.
  static constexpr int kPreviewRefresh = 4;
  void SetPreviewStep(int step) { preview_step_ = step == 1 || step == 4 ? step : 2; }
  int preview_step() const { return preview_step_; }
  // Clears a previous cancel: call (from any thread) before queueing ExportAsset, so that a
  // cancel pressed before the worker starts the export still counts.
  void ArmExport() { cancel_export_ = false; }

 public slots:
  // Opens the source and a fresh pipeline (the previous model is dropped).
  void Configure(const hdrf::gui::ScanSettings& settings);
  void Start();
  void Pause();
  void Stop();   // pause and rewind the source; the model stays until Reset/Configure
  void Reset();  // new empty model, source rewound
  // Exports: mesh (PLY), trajectory (TUM), the model ray cast from the current pose (EXR).
  // The PLY's display colours through `tone` ("OP[,key=value...]"): the model rendered
  // from the current pose sets the curve, as in the studio's model view and 3-D view.
  void ExportMesh(const QString& path, const QString& tone = QStringLiteral("mantiuk08"));
  void ExportTrajectory(const QString& path);
  void ExportRender(const QString& path);
  // The scan as textured HDR assets into a folder (io::ExportAsset: keyframes, mesh, the
  // model's render from the current pose as the tone reference). Progress and the result
  // come as assetProgress / assetDone; CancelExport stops it, leaving the folder as it was.
  void ExportAsset(const QString& folder, const hdrf::io::AssetOptions& options);
  // Project files (io/project.h). Save: the scan so far (answers with projectSaved). Open:
  // a saved scan, its source reopened and, for the same recorded source, positioned after
  // the frames already scanned; Start continues it (answers with projectOpened, or failed).
  void SaveProject(const QString& path);
  void OpenProject(const QString& path);
  // Before the window closes: a scan with frames not yet saved is autosaved one last time
  // (its recovery file is offered on the next start); a saved one leaves no recovery file.
  void Shutdown();
  // Live camera: exposure controls (the ae/awb/exposure/gain parts; unset ones stay).
  void SetCameraControls(const hdrf::sensors::LiveOptions& controls);
  // Records what the camera delivers from now on (scanning or not): a sequence folder
  // (absent or empty), or FILE.oni.
  void StartRecording(const QString& path);
  void StopRecording();
  // Lists the connected devices (answers with sensorsListed).
  void ListSensors();
  // Hot-plug events (from the window's monitor): a lost camera that comes back is reopened.
  void DeviceConnected(const QString& uri);

 signals:
  void snapshot(std::shared_ptr<const hdrf::gui::Snapshot> s);
  // The surface, meshed again off the scan's thread (last: from the scan's last frame).
  void meshUpdated(std::shared_ptr<const hdrf::mesh::Mesh> mesh, bool last);
  void stateChanged(bool running, const QString& message);
  void failed(const QString& message);  // the scan paused because of it
  void finished(int frames);            // the source is exhausted
  void exportProgress(double fraction);
  void exportDone(bool ok, const QString& message);
  void assetProgress(double fraction, const QString& stage);
  void assetDone(bool ok, const QString& message, const QImage& preview);
  void sensorsListed(const std::vector<hdrf::gui::SensorListing>& sensors);
  void recordingDone(bool ok, const QString& message);
  void cameraLost(const QString& message);  // the scan is paused, the model kept
  void cameraBack(const QString& message);
  void projectSaved(bool ok, const QString& path, const QString& message);
  void projectOpened(const hdrf::gui::ScanSettings& settings, const QString& path, const QString& message);

 private:
  void Kick();     // schedules Loop once
  void Loop();     // one frame: scanned while running, else previewed (live cameras)
  void Step();
  void Preview();
  void RequestMesh(bool last);  // the bricks changed since the last request, to the mesher
  void ResetMesher();           // a new model: the mesher starts empty
  void OnMesh(std::shared_ptr<const mesh::Mesh> m);
  void Open();
  void Autosave();  // the scan to its recovery file when due (jobs::ScanJob::Autosave)
  void DropJob();   // the model dropped on purpose, and its recovery file with it
  void Publish();             // a snapshot of the model as it stands (after opening a project)
  void FillScanState(Snapshot& s);  // trajectory, exposures, mesh, volume, device
  // The shared series brought up to the session's reports (only the new frames' values are
  // appended); ClearSeries where the session is replaced.
  void SyncSeries();
  void ClearSeries();
  void OpenSource();
  void Lost();     // the camera was unplugged: pause, keep the model, wait for it
  void TryReconnect(int attempt);
  void OnLiveFrame(const sensors::LiveFrame& f);  // frame rate, and the recording if one runs
  void FinishRecording(const QString& why);
  LiveStatus Status();
  ScanSettings settings_;
  SharedSeries<Pose> poses_;  // the snapshots' trajectory and exposure series (SyncSeries)
  SharedSeries<double> exposure_estimated_, exposure_reported_;
  std::unique_ptr<pipeline::FrameSource> source_;
  sensors::LiveFrameSource* live_ = nullptr;  // source_, when it is a live camera
  std::string source_spec_;                   // what source_ was opened from
  sensors::LiveOptions controls_;             // exposure controls in force (reapplied after a replug)
  sensors::ExposureState camera_state_;       // as the camera read back after the last change
  bool lost_ = false, resume_ = false, loop_scheduled_ = false, reconnecting_ = false;
  std::string lost_serial_;
  std::unique_ptr<sensors::SequenceRecorder> recorder_;
  std::unique_ptr<sensors::OniRecording> oni_;
  QString recording_path_;
  double fps_ = 0, last_frame_time_ = -1;
  std::unique_ptr<jobs::ScanJob> job_;  // the scan: its session, recovery file and project
  std::shared_ptr<const mesh::Mesh> mesh_;
  std::int64_t mesh_time_ms_ = 0, images_time_ms_ = 0;
  int mesh_frame_ = -1;             // the frame of the last mesh request
  int mesh_generation_ = 0;         // the model the mesher works on (one more at each reset)
  QThread* mesh_thread_ = nullptr;
  MeshWorker* mesher_ = nullptr;    // lives on mesh_thread_
  std::atomic<unsigned> shown_views_{0x1f};  // ViewSet as bits
  std::atomic<int> preview_step_{2};
  std::atomic<int> images_interval_ms_{0};
  bool running_ = false;
  std::atomic<bool> cancel_export_{false};
};

// Opens a source spec: "synthetic:key=value,..." (as `hdrfusion scan`), a sequence folder,
// a live camera "openni:..." or a recording FILE.oni. Throws hdrf::Error with the reason.
std::unique_ptr<pipeline::FrameSource> OpenFrameSource(const std::string& spec);

}  // namespace hdrf::gui

Q_DECLARE_METATYPE(hdrf::gui::ScanSettings)
Q_DECLARE_METATYPE(std::shared_ptr<const hdrf::gui::Snapshot>)
Q_DECLARE_METATYPE(hdrf::sensors::LiveOptions)
Q_DECLARE_METATYPE(std::vector<hdrf::gui::SensorListing>)
