// The pipeline on its own thread. The worker owns the frame source and the pipeline, runs
// frames while scanning, and publishes each result as an immutable snapshot (shared
// pointer): views take the latest and drop what they had no time for, so a slow view never
// stalls the scan. Errors from the source or the engine pause the scan with a message; the
// model built so far is kept.
#pragma once

#include <QObject>
#include <atomic>
#include <memory>
#include <optional>
#include <vector>

#include "mesh/mesh.h"
#include "pipeline/frame_source.h"
#include "pipeline/scan_session.h"

namespace hdrf::gui {

struct ScanSettings {
  std::string source = "synthetic:scene=room,frames=300,ae=flicker";  // as `hdrfusion scan` takes it
  pipeline::PipelineOptions pipeline;
  // Refresh of the 3-D view's mesh: every this many frames, and no more often than
  // mesh_min_interval_ms (fast GPU scans would otherwise spend their time meshing).
  int mesh_every_frames = 15;
  int mesh_min_interval_ms = 500;
};

// What one processed frame leaves for the views (all host copies, never modified).
struct Snapshot {
  pipeline::FrameReport report;
  ColorImage color;
  pipeline::FrameViews images;       // radiance, confidence, filtered depth, NR, ray cast
  PinholeCamera camera;
  std::vector<Pose> trajectory;      // every pose so far
  std::vector<double> exposure_estimated, exposure_reported;  // ratios per frame (reported: NaN if none)
  std::shared_ptr<const mesh::Mesh> mesh;  // latest extracted mesh (may be older than the frame)
  std::size_t volume_bytes = 0, bricks = 0;
  int frames_total = -1;             // of the source (-1: unbounded)
  std::string device;                // "cpu" or "cuda"
};

class ScanWorker : public QObject {
  Q_OBJECT
 public:
  ScanWorker();
  ~ScanWorker() override;
  bool running() const { return running_; }
  // Cancels an export in progress (any thread).
  void CancelExport() { cancel_export_ = true; }

 public slots:
  // Opens the source and a fresh pipeline (the previous model is dropped).
  void Configure(const hdrf::gui::ScanSettings& settings);
  void Start();
  void Pause();
  void Stop();   // pause and rewind the source; the model stays until Reset/Configure
  void Reset();  // new empty model, source rewound
  // Exports: mesh (PLY), trajectory (TUM), the model ray cast from the current pose (EXR).
  void ExportMesh(const QString& path);
  void ExportTrajectory(const QString& path);
  void ExportRender(const QString& path);

 signals:
  void snapshot(std::shared_ptr<const hdrf::gui::Snapshot> s);
  void stateChanged(bool running, const QString& message);
  void failed(const QString& message);  // the scan paused because of it
  void finished(int frames);            // the source is exhausted
  void exportProgress(double fraction);
  void exportDone(bool ok, const QString& message);

 private:
  void Step();
  void Open();
  ScanSettings settings_;
  std::unique_ptr<pipeline::FrameSource> source_;
  std::unique_ptr<pipeline::ScanSession> session_;
  std::shared_ptr<const mesh::Mesh> mesh_;
  std::int64_t mesh_time_ms_ = 0;
  bool running_ = false;
  std::atomic<bool> cancel_export_{false};
};

// Opens a source spec: "synthetic:key=value,..." (as `hdrfusion scan`), or a sequence
// folder. Throws hdrf::Error / InputError with the reason.
std::unique_ptr<pipeline::FrameSource> OpenFrameSource(const std::string& spec);

}  // namespace hdrf::gui

Q_DECLARE_METATYPE(hdrf::gui::ScanSettings)
Q_DECLARE_METATYPE(std::shared_ptr<const hdrf::gui::Snapshot>)
