#include "gui/scan_worker.h"

#include <QDateTime>
#include <QTimer>
#include <cmath>
#include <limits>

#include "common/error.h"
#include "io/exr.h"
#include "io/ply.h"
#include "io/source_spec.h"
#include "io/tum.h"

namespace hdrf::gui {

std::unique_ptr<pipeline::FrameSource> OpenFrameSource(const std::string& spec) {
  // Recorded sequences without a calibrated response fall back to sRGB in the studio (the
  // source's warning says so in the status bar); the CLI asks for --response srgb.
  return io::OpenSource(spec, "srgb");
}

ScanWorker::ScanWorker() {
  qRegisterMetaType<hdrf::gui::ScanSettings>();
  qRegisterMetaType<std::shared_ptr<const hdrf::gui::Snapshot>>();
}

ScanWorker::~ScanWorker() = default;

void ScanWorker::Open() {
  source_.reset();
  session_.reset();
  mesh_.reset();
  source_ = OpenFrameSource(settings_.source);
  session_ = std::make_unique<pipeline::ScanSession>(settings_.pipeline, source_->sensor().camera, source_->sensor());
}

void ScanWorker::Configure(const ScanSettings& s) {
  running_ = false;
  settings_ = s;
  try {
    Open();
    QString msg = tr("Ready: %1").arg(QString::fromStdString(source_->description()));
    const pipeline::Pipeline& pipe = session_->pipeline();
    if (!pipe.device_note().empty()) msg += " — " + QString::fromStdString(pipe.device_note());
    for (const std::string& w : source_->sensor().warnings) msg += " — " + QString::fromStdString(w);
    emit stateChanged(false, msg);
  } catch (const std::exception& e) {
    source_.reset();
    session_.reset();
    emit failed(tr("Cannot open the source: %1").arg(QString::fromStdString(e.what())));
    emit stateChanged(false, tr("No source"));
  }
}

void ScanWorker::Start() {
  if (!session_) {
    try {
      Open();
    } catch (const std::exception& e) {
      emit failed(tr("Cannot open the source: %1").arg(QString::fromStdString(e.what())));
      return;
    }
  }
  if (running_) return;
  running_ = true;
  emit stateChanged(true, tr("Scanning on the %1").arg(session_->pipeline().device() == Device::kCuda ? "GPU" : "CPU"));
  QTimer::singleShot(0, this, &ScanWorker::Step);
}

void ScanWorker::Pause() {
  if (!running_) return;
  running_ = false;
  emit stateChanged(false, tr("Paused after %1 frames").arg(session_ ? session_->frames() : 0));
}

void ScanWorker::Stop() {
  running_ = false;
  // Rewind the source; keep the model (export still possible) until Reset.
  try {
    if (session_) source_ = OpenFrameSource(settings_.source);
    emit stateChanged(false, tr("Stopped; the model of %1 frames is kept").arg(session_ ? session_->frames() : 0));
  } catch (const std::exception& e) {
    emit failed(QString::fromStdString(e.what()));
  }
}

void ScanWorker::Reset() {
  running_ = false;
  try {
    Open();
    emit stateChanged(false, tr("Reset: empty model"));
  } catch (const std::exception& e) {
    emit failed(QString::fromStdString(e.what()));
  }
}

void ScanWorker::Step() {
  if (!running_ || !session_) return;
  try {
    pipeline::FrameInput f;
    if (!source_->Next(f)) {
      running_ = false;
      emit finished(session_->frames());
      emit stateChanged(false, tr("Finished: %1 frames").arg(session_->frames()));
      return;
    }
    auto s = std::make_shared<Snapshot>();
    s->report = session_->Process(f);
    pipeline::Pipeline& pipe = session_->pipeline();
    const std::int64_t now = QDateTime::currentMSecsSinceEpoch();
    const bool last = source_->size() > 0 && s->report.index + 1 >= source_->size();
    if (!mesh_ || last ||
        (s->report.index % std::max(1, settings_.mesh_every_frames) == 0 &&
         now - mesh_time_ms_ >= settings_.mesh_min_interval_ms)) {
      mesh_ = std::make_shared<const mesh::Mesh>(pipe.ExtractMesh());
      mesh_time_ms_ = now;
    }
    s->color = std::move(f.color);
    s->images = pipe.DownloadViews();
    s->camera = source_->sensor().camera;
    s->trajectory = session_->poses();
    for (const pipeline::FrameReport& r : session_->reports()) {
      s->exposure_estimated.push_back(r.exposure_ratio);
      s->exposure_reported.push_back(r.exposure_ratio_reported.value_or(std::numeric_limits<double>::quiet_NaN()));
    }
    s->mesh = mesh_;
    s->volume_bytes = pipe.volume_stats().bytes;
    s->bricks = s->report.allocated_bricks;
    s->frames_total = source_->size();
    s->device = DeviceName(pipe.device());
    emit snapshot(std::move(s));
  } catch (const std::exception& e) {
    running_ = false;
    emit failed(tr("Scan paused at frame %1: %2. The model so far is kept.")
                    .arg(session_->frames())
                    .arg(QString::fromStdString(e.what())));
    emit stateChanged(false, tr("Paused (error)"));
    return;
  }
  QTimer::singleShot(0, this, &ScanWorker::Step);
}

void ScanWorker::ExportMesh(const QString& path) {
  cancel_export_ = false;
  if (!session_) {
    emit exportDone(false, tr("Nothing to export: no model"));
    return;
  }
  try {
    const mesh::Mesh m = session_->pipeline().ExtractMesh([this](double f) {
      emit exportProgress(0.9 * f);
      return !cancel_export_;
    });
    if (cancel_export_) throw Cancelled();
    io::WritePly(path.toStdString(), m);  // through a temporary file: nothing half-written
    emit exportProgress(1.0);
    emit exportDone(true, tr("Wrote %1 (%2 vertices, %3 triangles)").arg(path).arg(m.position.size()).arg(m.triangles.size()));
  } catch (const Cancelled&) {
    emit exportDone(false, tr("Mesh export cancelled; nothing was written"));
  } catch (const std::exception& e) {
    emit exportDone(false, tr("Mesh export: %1").arg(QString::fromStdString(e.what())));
  }
}

void ScanWorker::ExportTrajectory(const QString& path) {
  try {
    if (!session_) throw Error("no scan");
    std::vector<io::TimedPose> t;
    for (const pipeline::FrameReport& r : session_->reports()) t.push_back({r.timestamp, r.T_world_camera});
    io::WriteTrajectory(path.toStdString(), t);
    emit exportDone(true, tr("Wrote %1 (%2 poses)").arg(path).arg(t.size()));
  } catch (const std::exception& e) {
    emit exportDone(false, tr("Trajectory export: %1").arg(QString::fromStdString(e.what())));
  }
}

void ScanWorker::ExportRender(const QString& path) {
  try {
    if (!session_) throw Error("no model");
    const auto r = session_->pipeline().Render(session_->pipeline().pose());
    io::WriteExr(path.toStdString(), r.radiance);
    emit exportDone(true, tr("Wrote %1").arg(path));
  } catch (const std::exception& e) {
    emit exportDone(false, tr("OpenEXR export: %1").arg(QString::fromStdString(e.what())));
  }
}

}  // namespace hdrf::gui
