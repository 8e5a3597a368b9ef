#include "gui/scan_worker.h"

#include <QDateTime>
#include <QTimer>
#include <sys/resource.h>

#include "gui/language/language.h"
#include "io/project.h"
#include "io/source_spec.h"
#include "jobs/scan_job.h"

namespace hdrf::gui {

std::unique_ptr<pipeline::FrameSource> OpenFrameSource(const std::string& spec) {
  // Recorded sequences without a calibrated response fall back to sRGB in the studio (the
  // source's warning says so in the status bar); the CLI asks for --response srgb.
  return sensors::OpenAnySource(spec, "srgb");
}

void MeshWorker::Reset(const volume::VolumeOptions& o) { mesher_ = std::make_unique<mesh::IncrementalMesher>(o); }

void MeshWorker::Apply(const std::shared_ptr<const volume::BrickSet>& changed, bool last, int generation, int step,
                       int refresh_after) {
  std::shared_ptr<const mesh::Mesh> m;
  if (mesher_) {
    mesher_->Apply(*changed, step, refresh_after);
    m = std::make_shared<const mesh::Mesh>(mesher_->Assemble(step));
  }
  busy = false;
  if (m) emit meshReady(std::move(m), last, generation);
}

ScanWorker::ScanWorker() {
  qRegisterMetaType<std::shared_ptr<const hdrf::mesh::Mesh>>();
  mesh_thread_ = new QThread;
  mesh_thread_->setObjectName("mesher");
  mesher_ = new MeshWorker;
  mesher_->moveToThread(mesh_thread_);
  // The mesher yields to the scan: below its priority (a nice value for this thread alone).
  connect(mesh_thread_, &QThread::started, mesher_, [] { setpriority(PRIO_PROCESS, id_t(syscall(SYS_gettid)), 5); });
  connect(mesher_, &MeshWorker::meshReady, this, [this](std::shared_ptr<const mesh::Mesh> m, bool last, int generation) {
    if (generation != mesh_generation_) return;  // the surface of a model since dropped
    OnMesh(m);
    emit meshUpdated(std::move(m), last);
  });
  mesh_thread_->start();
  qRegisterMetaType<hdrf::gui::ScanSettings>();
  qRegisterMetaType<hdrf::io::AssetOptions>();
  qRegisterMetaType<std::shared_ptr<const hdrf::gui::Snapshot>>();
  qRegisterMetaType<hdrf::sensors::LiveOptions>();
  qRegisterMetaType<std::vector<hdrf::gui::SensorListing>>();
}

ScanWorker::~ScanWorker() {
  // A recording in progress is closed with every frame written.
  if (recorder_) recorder_->Finish();
  mesh_thread_->quit();
  mesh_thread_->wait();
  delete mesher_;
  delete mesh_thread_;
}

void ScanWorker::SetShownViews(const pipeline::ViewSet& v) {
  shown_views_ = unsigned(v.radiance) | unsigned(v.confidence) << 1 | unsigned(v.nr) << 2 | unsigned(v.depth) << 3 |
                 unsigned(v.render) << 4;
}
pipeline::ViewSet ScanWorker::ShownViews() const {
  const unsigned b = shown_views_;
  return {(b & 1) != 0, (b & 2) != 0, (b & 4) != 0, (b & 8) != 0, (b & 16) != 0};
}

void ScanWorker::ResetMesher() {
  mesh_.reset();
  mesh_frame_ = -1;
  ++mesh_generation_;
  mesher_->busy = false;
  const volume::VolumeOptions o = job_->session().pipeline().options().volume;
  QMetaObject::invokeMethod(mesher_, [m = mesher_, o] { m->Reset(o); }, Qt::QueuedConnection);
}

void ScanWorker::RequestMesh(bool last) {
  if (!job_) return;
  auto changed = std::make_shared<const volume::BrickSet>(job_->session().pipeline().ChangedBricks());
  mesher_->busy = true;
  mesh_time_ms_ = QDateTime::currentMSecsSinceEpoch();
  mesh_frame_ = job_->session().frames() - 1;
  // The whole surface at a stop (last), else the detail chosen for a running scan.
  const int step = last ? 1 : preview_step_.load();
  const int refresh = step > 1 ? kPreviewRefresh : 0;
  QMetaObject::invokeMethod(
      mesher_, [m = mesher_, changed, last, g = mesh_generation_, step, refresh] { m->Apply(changed, last, g, step, refresh); },
      Qt::QueuedConnection);
}

void ScanWorker::OnMesh(std::shared_ptr<const mesh::Mesh> m) { mesh_ = std::move(m); }


void ScanWorker::OpenSource() {
  if (recorder_ || oni_) FinishRecording(tr("the source was changed"));
  live_ = nullptr;
  source_.reset();
  lost_ = false;
  source_ = OpenFrameSource(settings_.source);
  source_spec_ = settings_.source;
  live_ = dynamic_cast<sensors::LiveFrameSource*>(source_.get());
  if (live_) {
    // The spec's exposure parts are what a replug sets again (ApplyExposure reads only those).
    controls_ = sensors::ParseLiveSpec(settings_.source);
    camera_state_ = live_->camera().exposure();
    fps_ = 0;
    last_frame_time_ = -1;
  }
}

void ScanWorker::Open() {
  const std::unique_ptr<jobs::ScanJob> previous = std::move(job_);
  mesh_.reset();
  // A live camera already streaming from the same spec stays open (and keeps recording):
  // only the model starts again.
  if (!(live_ && source_spec_ == settings_.source && !lost_)) OpenSource();
  job_ = std::make_unique<jobs::ScanJob>(settings_.pipeline, source_->sensor(), "studio", settings_.autosave_s);
  job_->SetSource(source_->description(), source_spec_);
  // The previous model was dropped on purpose: so is its recovery file (kept where the new
  // source could not be opened).
  if (previous) previous->DropRecovery();
  ClearSeries();
  ResetMesher();
  images_time_ms_ = 0;
}

void ScanWorker::DropJob() {
  if (job_) job_->DropRecovery();
  job_.reset();
}

void ScanWorker::Autosave() {
  if (!job_) return;
  if (const std::string e = job_->Autosave(); !e.empty())
    emit failed(tr("Autosave failed (the scan goes on): %1").arg(QString::fromStdString(e)));
}

void ScanWorker::SaveProject(const QString& path) {
  if (!job_ || job_->session().frames() == 0) {
    emit projectSaved(false, path, tr("Nothing to save: no frame has been scanned yet"));
    return;
  }
  try {
    const std::filesystem::path file = path.toStdString();
    job_->Save(file, true);
    std::error_code ec;
    emit projectSaved(true, path, tr("Saved %1 frames to %2 (%L3 MiB)")
                                      .arg(job_->session().frames())
                                      .arg(path)
                                      .arg(double(std::filesystem::file_size(file, ec)) / (1 << 20), 0, 'f', 1));
  } catch (const std::exception& e) {
    emit projectSaved(false, path, tr("Cannot save the project: %1").arg(QString::fromStdString(e.what())));
  }
}

void ScanWorker::OpenProject(const QString& path) {
  running_ = false;
  resume_ = false;
  try {
    const io::Project p = io::LoadProject(path.toStdString());
    auto job = std::make_unique<jobs::ScanJob>(p, nullptr, "studio", settings_.autosave_s);
    DropJob();
    job_ = std::move(job);
    ClearSeries();
    ResetMesher();
    settings_.pipeline = job_->session().pipeline().options();
    if (!p.source_spec.empty()) settings_.source = p.source_spec;
    QString msg = tr("Opened %1: %2 frames").arg(path).arg(job_->session().frames());
    if (!job_->notice().empty()) msg += " — " + language::EngineText(job_->notice());
    const QString src = QString::fromStdString(p.source);
    try {
      if (p.source_spec.empty()) throw Error("the project does not say how its source was opened");
      OpenSource();
      switch (job_->Continue(p, *source_, source_spec_)) {
        case jobs::ContinueFrom::kOtherCamera:
          source_.reset();
          live_ = nullptr;
          msg += tr(" — its source has another camera now: choose the source it was scanned with to continue");
          break;
        case jobs::ContinueFrom::kOtherResponse:
          source_.reset();
          live_ = nullptr;
          msg += tr(" — its source has another camera response now (its calibration changed): choose the source "
                    "it was scanned with to continue");
          break;
        case jobs::ContinueFrom::kAfterScanned:
          msg += tr(" — Start continues after frame %1").arg(p.resume.frames);
          break;
        case jobs::ContinueFrom::kNothingLeft:
          msg += tr(" — its source has no frames left");
          break;
        case jobs::ContinueFrom::kFirstFrame:
          msg += tr(" — Start continues from the first frame of %1, which must be where the scan stopped")
                     .arg(QString::fromStdString(source_->description()));
          break;
      }
    } catch (const std::exception& e) {
      source_.reset();
      live_ = nullptr;
      msg += tr(" — its source (%1) cannot be opened: %2").arg(src, QString::fromStdString(e.what()));
    }
    Publish();
    emit projectOpened(settings_, path, msg);
    emit stateChanged(false, msg);
  } catch (const std::exception& e) {
    emit failed(tr("Cannot open the project: %1").arg(QString::fromStdString(e.what())));
  }
}

void ScanWorker::Shutdown() {
  running_ = false;
  if (job_) job_->Close();
}

void ScanWorker::Publish() {
  if (!job_) return;
  auto s = std::make_shared<Snapshot>();
  pipeline::Pipeline& pipe = job_->session().pipeline();
  RequestMesh(true);  // the whole model (every brick is new to the mesher): meshUpdated follows
  if (!job_->session().reports().empty()) s->report = job_->session().reports().back();
  s->images.render = pipe.Render(pipe.pose());
  s->has_images = true;
  FillScanState(*s);
  emit snapshot(std::move(s));
}

void ScanWorker::ClearSeries() {
  poses_.Clear();
  exposure_estimated_.Clear();
  exposure_reported_.Clear();
}

void ScanWorker::SyncSeries() {
  const std::vector<pipeline::FrameReport>& reports = job_->session().reports();
  if (poses_.size() > reports.size()) ClearSeries();
  for (std::size_t i = poses_.size(); i < reports.size(); ++i) {
    const pipeline::FrameReport& r = reports[i];
    poses_.Append(r.T_world_camera);
    exposure_estimated_.Append(r.exposure_ratio);
    exposure_reported_.Append(r.exposure_ratio_reported.value_or(std::numeric_limits<double>::quiet_NaN()));
  }
}

void ScanWorker::FillScanState(Snapshot& s) {
  const pipeline::Pipeline& pipe = job_->session().pipeline();
  s.camera = job_->session().sensor().camera;
  SyncSeries();
  s.trajectory = poses_.prefix();
  s.exposure_estimated = exposure_estimated_.prefix();
  s.exposure_reported = exposure_reported_.prefix();
  s.mesh = mesh_;
  const pipeline::VolumeStats vs = pipe.volume_stats();
  s.volume_bytes = vs.bytes;
  s.volume_full = vs.full_reason;
  s.volume_bounds = vs.bounds;
  s.raycast_far_m = pipe.options().volume.raycast_far_m;
  s.volume_budget_mb = pipe.options().volume.max_memory_mb;
  s.gpu_budget_mb = pipe.options().volume.gpu_memory_mb;
  s.streaming = vs.streaming;
  s.bricks = vs.allocated_bricks;
  s.frames_total = source_ ? source_->size() : -1;
  s.device = DeviceName(pipe.device());
}

void ScanWorker::Configure(const ScanSettings& s) {
  running_ = false;
  settings_ = s;
  try {
    if (sensors::IsLiveSpec(s.source)) emit stateChanged(false, tr("Opening the camera…"));
    Open();
    QString msg = tr("Ready: %1").arg(QString::fromStdString(source_->description()));
    if (live_) msg = tr("Live preview: %1 (Start scans)").arg(QString::fromStdString(source_->description()));
    const pipeline::Pipeline& pipe = job_->session().pipeline();
    if (!pipe.device_note().empty()) msg += " — " + language::EngineText(pipe.device_note());
    if (!pipe.settings_note().empty()) msg += " — " + language::EngineText(pipe.settings_note());
    for (const std::string& w : source_->sensor().warnings) msg += " — " + language::EngineText(w);
    if (!job_->notice().empty()) msg += " — " + language::EngineText(job_->notice());
    emit stateChanged(false, msg);
    if (live_) {
      ListSensors();
      Kick();
    }
  } catch (const std::exception& e) {
    live_ = nullptr;
    source_.reset();
    job_.reset();
    emit failed(tr("Cannot open the source: %1").arg(QString::fromStdString(e.what())));
    emit stateChanged(false, tr("No source"));
  }
}

void ScanWorker::Kick() {
  if (loop_scheduled_) return;
  loop_scheduled_ = true;
  QTimer::singleShot(0, this, &ScanWorker::Loop);
}

void ScanWorker::Loop() {
  loop_scheduled_ = false;
  if (running_ && job_)
    Step();
  else if (live_ && !lost_)
    Preview();
  else
    return;
  if ((running_ && job_) || (live_ && !lost_)) Kick();
}

void ScanWorker::Start() {
  if (lost_) {
    // The camera went away: try it again now (the button says Resume).
    resume_ = true;
    TryReconnect(0);
    return;
  }
  if (!job_) {
    try {
      Open();
    } catch (const std::exception& e) {
      emit failed(tr("Cannot open the source: %1").arg(QString::fromStdString(e.what())));
      return;
    }
  }
  if (!source_) {
    emit failed(tr("No source to continue from: choose one (Source) and Open the project again, or Reset"));
    return;
  }
  if (running_) return;
  running_ = true;
  emit stateChanged(true, tr("Scanning on the %1").arg(job_->session().pipeline().device() == Device::kCuda ? "GPU" : "CPU"));
  Kick();
}

void ScanWorker::Pause() {
  resume_ = false;
  if (!running_) return;
  running_ = false;
  // The surface as it stands when the scan stops.
  if (job_ && job_->session().frames() > 0) RequestMesh(true);
  emit stateChanged(false, tr("Paused after %1 frames").arg(job_ ? job_->session().frames() : 0));
}

void ScanWorker::Stop() {
  running_ = false;
  resume_ = false;
  // Rewind the source; keep the model (export still possible) until Reset. A live camera
  // has nothing to rewind: it stays open and previews.
  try {
    if (job_ && !live_ && !lost_) source_ = OpenFrameSource(settings_.source);
    emit stateChanged(false, tr("Stopped; the model of %1 frames is kept").arg(job_ ? job_->session().frames() : 0));
  } catch (const std::exception& e) {
    emit failed(QString::fromStdString(e.what()));
  }
}

void ScanWorker::Reset() {
  running_ = false;
  resume_ = false;
  try {
    Open();
    emit stateChanged(false, tr("Reset: empty model"));
    if (live_) Kick();
  } catch (const std::exception& e) {
    emit failed(QString::fromStdString(e.what()));
  }
}

void ScanWorker::Step() {
  if (!running_ || !job_) return;
  try {
    pipeline::FrameInput f;
    if (!source_->Next(f)) {
      running_ = false;
      emit finished(job_->session().frames());
      emit stateChanged(false, tr("Finished: %1 frames").arg(job_->session().frames()));
      return;
    }
    if (live_) OnLiveFrame(live_->last());
    auto s = std::make_shared<Snapshot>();
    s->report = job_->session().Process(f);
    pipeline::Pipeline& pipe = job_->session().pipeline();
    const std::int64_t now = QDateTime::currentMSecsSinceEpoch();
    const bool last = source_->size() > 0 && s->report.index + 1 >= source_->size();
    // The surface: the bricks changed since the last refresh go to the mesher's thread.
    if (last || (!mesher_->busy && (mesh_frame_ < 0 || (job_->session().frames() - 1 - mesh_frame_ >=
                                                             std::max(1, settings_.mesh_every_frames) &&
                                                         now - mesh_time_ms_ >= settings_.mesh_min_interval_ms))))
      RequestMesh(last);
    s->color = std::move(f.color);
    if (const int k = s->report.nearest_entry; !s->report.fused && k >= 0 &&
                                              k < int(pipe.relocaliser().entries().size())) {
      s->reloc_hint = pipe.relocaliser().entries()[std::size_t(k)].thumbnail.Clone();
      s->reloc_hint_frame = pipe.relocaliser().entries()[std::size_t(k)].frame;
    }
    // The stage images on screen, at the display's rate (always on a scan's first and last).
    const int images_ms = std::max(settings_.images_min_interval_ms, images_interval_ms_.load());
    if (images_ms <= 0 || images_time_ms_ == 0 || last || now - images_time_ms_ >= images_ms) {
      s->images = pipe.DownloadViews(ShownViews());
      s->has_images = true;
      images_time_ms_ = now;
    }
    FillScanState(*s);
    if (live_) s->live = Status();
    emit snapshot(std::move(s));
    Autosave();
  } catch (const sensors::DeviceLost&) {
    Lost();
  } catch (const std::exception& e) {
    running_ = false;
    emit failed(tr("Scan paused at frame %1: %2. The model so far is kept.")
                    .arg(job_->session().frames())
                    .arg(QString::fromStdString(e.what())));
    emit stateChanged(false, tr("Paused (error)"));
  }
}

}  // namespace hdrf::gui
