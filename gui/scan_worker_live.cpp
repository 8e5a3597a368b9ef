// ScanWorker and the live camera: the preview while not scanning, the camera's status and
// controls, recording, the sensor list, and an unplugged camera waited for and reopened.
#include "gui/scan_worker.h"

#include <QTimer>

#include "io/image_io.h"

namespace hdrf::gui {

namespace {

QString Describe(const sensors::DeviceEntry& e) {
  return e.serial.empty() ? QString::fromStdString(e.name)
                          : QStringLiteral("%1 (%2)").arg(QString::fromStdString(e.serial), QString::fromStdString(e.name));
}

}  // namespace

void ScanWorker::Preview() {
  try {
    const sensors::LiveFrame f = live_->NextFrame();
    OnLiveFrame(f);
    auto s = std::make_shared<Snapshot>();
    s->preview = true;
    s->color = f.color.Clone();
    s->images.depth = io::DepthToMetres(f.depth_mm, live_->sensor().depth_scale);
    s->camera = live_->sensor().camera;
    if (job_) {
      SyncSeries();
      s->trajectory = poses_.prefix();
      s->report.index = job_->session().frames() - 1;
    }
    s->mesh = mesh_;
    s->frames_total = source_->size();
    s->live = Status();
    emit snapshot(std::move(s));
  } catch (const sensors::DeviceLost&) {
    Lost();
  } catch (const std::exception& e) {
    // No frame in time, or the device failed: say so and keep trying (a camera that stops
    // sending is reported every 2 s, not silently shown as a frozen picture).
    emit failed(tr("Live preview: %1").arg(QString::fromStdString(e.what())));
  }
}

LiveStatus ScanWorker::Status() {
  LiveStatus st;
  sensors::OpenNiCamera& cam = live_->camera();
  st.device = cam.entry();
  st.has_camera_settings = cam.has_camera_settings();
  // As read back when last set (reading the device's properties every frame would cost a
  // round trip to the camera per frame).
  st.exposure = camera_state_;
  const auto& dev = live_->profile().sensor.device;
  if (dev && dev->exposure_ms_per_unit) st.ms_per_unit = dev->exposure_ms_per_unit;
  st.own_profile = live_->profile().own;
  st.dropped = cam.dropped();
  st.fps = fps_;
  st.recording = recorder_ || oni_;
  st.recording_path = recording_path_.toStdString();
  if (recorder_) st.recording_stats = recorder_->stats();
  return st;
}

void ScanWorker::OnLiveFrame(const sensors::LiveFrame& f) {
  // Frame rate from the device clock (recent frames weigh most).
  if (last_frame_time_ >= 0 && f.timestamp > last_frame_time_) {
    const double r = 1.0 / (f.timestamp - last_frame_time_);
    fps_ = fps_ > 0 ? 0.9 * fps_ + 0.1 * r : r;
  }
  last_frame_time_ = f.timestamp;
  const std::optional<double> ms = live_->ExposureMs(f);
  const std::optional<double> gain = f.GainFactor();
  if (recorder_) {
    recorder_->Push(f.Clone(), ms, gain);
    if (recorder_->failed()) FinishRecording(QString());
  } else if (oni_) {
    try {
      oni_->NoteFrame(f, ms, gain);
    } catch (const std::exception& e) {
      FinishRecording(QString::fromStdString(e.what()));
    }
  }
}

void ScanWorker::StartRecording(const QString& path) {
  if (!live_ || lost_) {
    emit recordingDone(false, tr("Nothing to record: open a live camera first"));
    return;
  }
  if (recorder_ || oni_) {
    emit recordingDone(false, tr("Already recording to %1").arg(recording_path_));
    return;
  }
  try {
    const std::filesystem::path p = path.toStdString();
    if (p.extension() == ".oni")
      oni_ = std::make_unique<sensors::OniRecording>(p, live_->camera(), live_->sensor());
    else
      recorder_ = std::make_unique<sensors::SequenceRecorder>(p, live_->sensor());
    recording_path_ = path;
    emit stateChanged(running_, tr("Recording to %1").arg(path));
    Kick();
  } catch (const std::exception& e) {
    recorder_.reset();
    oni_.reset();
    emit recordingDone(false, tr("Cannot record: %1").arg(QString::fromStdString(e.what())));
  }
}

void ScanWorker::StopRecording() { FinishRecording(QString()); }

void ScanWorker::FinishRecording(const QString& why) {
  if (recorder_) {
    const sensors::RecordingStats st = recorder_->Finish();
    recorder_.reset();
    QString msg = tr("Recorded %1 frames (%L2 MB, %L3 s, %4 dropped) to %5")
                      .arg(st.written)
                      .arg(st.bytes / 1e6, 0, 'f', 1)
                      .arg(st.seconds, 0, 'f', 1)
                      .arg(st.dropped)
                      .arg(recording_path_);
    const bool ok = st.error.empty() && why.isEmpty();
    if (!st.error.empty()) msg = tr("Recording ended early: %1. %2").arg(QString::fromStdString(st.error), msg);
    if (!why.isEmpty()) msg = tr("Recording ended: %1. %2").arg(why, msg);
    emit recordingDone(ok && st.dropped == 0, msg);
  } else if (oni_) {
    oni_->Stop();
    oni_.reset();
    QString msg = tr("Recorded %1").arg(recording_path_);
    if (!why.isEmpty()) msg = tr("Recording ended: %1. %2").arg(why, msg);
    emit recordingDone(why.isEmpty(), msg);
  }
  recording_path_.clear();
}

void ScanWorker::SetCameraControls(const sensors::LiveOptions& c) {
  if (!live_ || lost_) {
    emit failed(tr("Camera settings: no live camera is open"));
    return;
  }
  try {
    live_->ApplyExposure(c);
    if (c.auto_exposure) controls_.auto_exposure = c.auto_exposure;
    if (c.auto_white_balance) controls_.auto_white_balance = c.auto_white_balance;
    if (c.exposure_ms || c.exposure_raw) {
      controls_.exposure_ms = c.exposure_ms;
      controls_.exposure_raw = c.exposure_raw;
      controls_.auto_exposure = false;
    }
    if (c.auto_exposure && *c.auto_exposure) controls_.exposure_ms.reset(), controls_.exposure_raw.reset();
    if (c.gain) controls_.gain = c.gain;
    const sensors::ExposureState e = camera_state_ = live_->camera().exposure();
    emit stateChanged(running_, tr("Camera: auto exposure %1, white balance %2, exposure %3, gain %4")
                                    .arg(e.auto_exposure ? tr("on") : tr("off"))
                                    .arg(e.auto_white_balance ? tr("auto") : tr("fixed"))
                                    .arg(e.exposure_raw)
                                    .arg(e.gain));
  } catch (const std::exception& e) {
    emit failed(tr("Camera settings: %1").arg(QString::fromStdString(e.what())));
  }
  if (!running_) Kick();
}

void ScanWorker::ListSensors() {
  std::vector<SensorListing> out;
  try {
    std::vector<sensors::DeviceEntry> known;
    if (live_ && !lost_) known.push_back(live_->camera().entry());
    for (const sensors::DeviceEntry& e : sensors::ListDevices(known)) {
      SensorListing l;
      l.entry = e;
      l.own_profile = !e.serial.empty() && std::filesystem::exists(sensors::ProfilePath(e.serial));
      l.in_use = !known.empty() && known.front().uri == e.uri;
      out.push_back(l);
    }
  } catch (const std::exception& e) {
    emit failed(tr("Listing cameras: %1").arg(QString::fromStdString(e.what())));
  }
  emit sensorsListed(out);
}

void ScanWorker::Lost() {
  const bool was_running = running_;
  running_ = false;
  lost_ = true;
  resume_ = was_running;
  lost_serial_ = live_ ? live_->camera().entry().serial : std::string();
  const QString who = live_ ? Describe(live_->camera().entry()) : tr("the camera");
  FinishRecording(tr("%1 was unplugged").arg(who));
  live_ = nullptr;
  source_.reset();
  // The surface of the model as it is kept.
  if (was_running && job_ && job_->session().frames() > 0) RequestMesh(true);
  const int frames = job_ ? job_->session().frames() : 0;
  const QString msg = was_running
      ? tr("Camera %1 was unplugged: the scan is paused after %2 frames and the model is kept. "
           "Plug it back in to resume.").arg(who).arg(frames)
      : tr("Camera %1 was unplugged. Plug it back in to continue.").arg(who);
  emit cameraLost(msg);
  emit stateChanged(false, tr("Camera unplugged; waiting for it to come back"));
  ListSensors();
}

void ScanWorker::DeviceConnected(const QString&) {
  ListSensors();
  if (lost_ && !reconnecting_) TryReconnect(0);
}

void ScanWorker::TryReconnect(int attempt) {
  if (!lost_) return;
  reconnecting_ = true;
  try {
    auto src = OpenFrameSource(settings_.source);
    auto* live = dynamic_cast<sensors::LiveFrameSource*>(src.get());
    if (!live) throw Error("the source is no longer a live camera");
    if (!lost_serial_.empty() && live->camera().entry().serial != lost_serial_) {
      // Another camera: its calibration and its view are not this model's.
      reconnecting_ = false;
      emit failed(tr("Camera %1 was connected, but this scan was made with %2: plug that one back in, or Reset "
                     "to start a new scan")
                      .arg(Describe(live->camera().entry()), QString::fromStdString(lost_serial_)));
      return;
    }
    live->ApplyExposure(controls_);
    camera_state_ = live->camera().exposure();
    source_ = std::move(src);
    live_ = live;
    lost_ = false;
    reconnecting_ = false;
    fps_ = 0;
    last_frame_time_ = -1;
    const int frames = job_ ? job_->session().frames() : 0;
    if (resume_ && job_) {
      running_ = true;
      emit cameraBack(tr("Camera %1 is back: the scan resumes at frame %2").arg(Describe(live_->camera().entry())).arg(frames + 1));
      emit stateChanged(true, tr("Scanning (resumed after a reconnect)"));
    } else {
      emit cameraBack(tr("Camera %1 is back").arg(Describe(live_->camera().entry())));
      emit stateChanged(false, tr("Live preview (the model of %1 frames is kept; Start continues it)").arg(frames));
    }
    resume_ = false;
    ListSensors();
    Kick();
  } catch (const std::exception& e) {
    // The device may take a moment to answer after it appears: a few tries, then say why.
    if (attempt < 10) {
      QTimer::singleShot(500, this, [this, attempt] { TryReconnect(attempt + 1); });
      return;
    }
    reconnecting_ = false;
    emit failed(tr("The camera came back but could not be reopened: %1").arg(QString::fromStdString(e.what())));
  }
}

}  // namespace hdrf::gui
