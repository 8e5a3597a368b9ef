#include "sensors/live_source.h"

#include <OpenNI.h>

#include <cmath>
#include <cstring>
#include <deque>
#include <map>
#include <sstream>

#include "common/message.h"
#include "common/input_file.h"
#include "io/image_io.h"
#include "io/sensor_json.h"
#include "io/source_spec.h"
#include "sensors/frame_pairing.h"
#include "sim/builtin_sensor.h"

namespace hdrf::sensors {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

bool OnOff(const std::string& key, const std::string& v) {
  if (v == "on" || v == "1" || v == "true") return true;
  if (v == "off" || v == "0" || v == "false") return false;
  throw SettingError(key, "expected on or off, got '" + v + "'");
}

// The engine is told exposure time x analog gain (`gain`: a linear factor, 1 at the device's
// unit gain) as the frame's exposure: the signal grows with both, and only ratios matter. A
// recording scanned later is told the same (io::SequenceFrameSource).
pipeline::FrameInput ToInput(const LiveFrame& f, double depth_scale, std::optional<double> exposure_ms,
                             std::optional<double> gain) {
  pipeline::FrameInput in;
  in.color = f.color.Clone();
  in.depth_m = io::DepthToMetres(f.depth_mm, depth_scale);
  in.timestamp = f.timestamp;
  in.exposure_ms = exposure_ms;
  if (in.exposure_ms && gain) *in.exposure_ms *= *gain;
  return in;
}

// FNV-1a over the colour bytes: how the .oni exposure sidecar names a frame.
std::uint64_t Fingerprint(const ColorImage& c) {
  std::uint64_t h = 1469598103934665603ull;
  const auto* p = reinterpret_cast<const std::uint8_t*>(c.data());
  for (std::size_t k = 0, n = c.size() * 3; k < n; ++k) h = (h ^ p[k]) * 1099511628211ull;
  return h;
}

}  // namespace

bool IsLiveSpec(const std::string& spec) { return spec.rfind("openni:", 0) == 0; }

LiveOptions ParseLiveSpec(const std::string& spec) {
  if (!IsLiveSpec(spec)) throw SettingError("SOURCE", "'" + spec + "' is not a live source (openni:...)");
  LiveOptions o;
  for (const auto& [k, v] : io::SplitSpec(spec, 7, "openni:device=SERIAL,mode=vga,ae=off,exposure=10")) {
    try {
      std::size_t used = 0;
      auto number = [&](auto parse) {
        const auto value = parse(v, &used);
        if (used != v.size()) throw std::invalid_argument(v);
        return value;
      };
      if (k == "device") o.device = v;
      else if (k == "mode") o.mode = ParseCaptureMode(v);
      else if (k == "ae") o.auto_exposure = OnOff("ae", v);
      else if (k == "awb") o.auto_white_balance = OnOff("awb", v);
      else if (k == "exposure") o.exposure_ms = number([](const std::string& s, std::size_t* u) { return std::stod(s, u); });
      else if (k == "exposure_raw") o.exposure_raw = number([](const std::string& s, std::size_t* u) { return std::stoi(s, u); });
      else if (k == "gain") o.gain = number([](const std::string& s, std::size_t* u) { return std::stoi(s, u); });
      else if (k == "frames") o.frames = number([](const std::string& s, std::size_t* u) { return std::stoi(s, u); });
      else
        throw SettingError("SOURCE", "unknown live setting '" + k +
                                         "' (device, mode, ae, awb, exposure, exposure_raw, gain, frames)");
    } catch (const std::logic_error&) {
      throw SettingError("SOURCE", "cannot parse '" + k + "=" + v + "' in '" + spec + "'");
    }
  }
  if (o.exposure_ms && !(*o.exposure_ms > 0)) throw SettingError("exposure", "must be positive milliseconds");
  if (o.exposure_ms && o.exposure_raw) throw SettingError("exposure", "give exposure (ms) or exposure_raw, not both");
  if ((o.exposure_ms || o.exposure_raw) && o.auto_exposure.value_or(false))
    throw SettingError("exposure", "a fixed exposure needs ae=off");
  if ((o.exposure_ms || o.exposure_raw)) o.auto_exposure = false;
  if (o.frames == 0 || o.frames < -1) throw SettingError("frames", "must be positive");
  return o;
}

// ---- live -----------------------------------------------------------------------------------

LiveFrameSource::LiveFrameSource(LiveOptions options) : options_(std::move(options)) {
  camera_ = OpenNiCamera::Open(options_.device, options_.mode);
  profile_ = ProfileFor(camera_->entry(), options_.mode);
  if (!camera_->depth_registered_by_device())
    profile_.sensor.warnings.push_back(Say(words::kNoDepthRegistration, {camera_->entry().name}));
  ApplyExposure(options_);
}

void LiveFrameSource::ApplyExposure(const LiveOptions& o) {
  const bool wants = o.auto_exposure || o.auto_white_balance || o.exposure_ms || o.exposure_raw || o.gain;
  if (!wants) return;
  if (!camera_->has_camera_settings())
    throw SensorError("device '" + camera_->entry().name + "' (" + camera_->entry().uri +
                      ") has no camera settings: auto exposure, white balance, exposure and gain cannot be set");
  if (o.auto_white_balance) camera_->SetAutoWhiteBalance(*o.auto_white_balance);
  if (o.auto_exposure) camera_->SetAutoExposure(*o.auto_exposure);
  std::optional<int> raw = o.exposure_raw;
  if (o.exposure_ms) {
    const auto& dev = profile_.sensor.device;
    if (!dev || !dev->exposure_ms_per_unit)
      throw SettingError("exposure", "the profile of this device gives no exposure unit "
                                     "(hdrfusion.device.exposure_ms_per_unit), so milliseconds cannot be "
                                     "converted; give exposure_raw in the device's unit instead");
    raw = int(std::lround(*o.exposure_ms / *dev->exposure_ms_per_unit));
    if (*raw < 1) raw = 1;
  }
  if (raw) camera_->SetExposure(*raw);
  if (o.gain) camera_->SetGain(*o.gain);
  camera_->Flush();  // frames from now on are taken under these settings
}

std::optional<double> LiveFrameSource::ExposureMs(const LiveFrame& f) const {
  const auto& dev = profile_.sensor.device;
  if (!f.exposure_raw || !dev || !dev->exposure_ms_per_unit) return std::nullopt;
  return *f.exposure_raw * *dev->exposure_ms_per_unit;
}

LiveFrame LiveFrameSource::NextFrame() {
  std::optional<LiveFrame> f = camera_->Read(2000ms);
  if (!f) throw SensorError("device '" + camera_->entry().name + "' sent no frame for 2 s");
  ++delivered_;
  return std::move(*f);
}

bool LiveFrameSource::Next(pipeline::FrameInput& frame) {
  if (options_.frames > 0 && delivered_ >= options_.frames) return false;
  last_ = NextFrame();
  frame = ToInput(last_, profile_.sensor.depth_scale, ExposureMs(last_), last_.GainFactor());
  return true;
}

std::string LiveFrameSource::description() const {
  return "live device '" + camera_->entry().name + "' (" + camera_->entry().uri + ", " +
         std::to_string(options_.mode.width) + "x" + std::to_string(options_.mode.height) + ")";
}

// ---- .oni recording --------------------------------------------------------------------------

struct OniRecording::Impl {
  OpenNiCamera* camera;
  std::ofstream sidecar;
  fs::path file;
};

OniRecording::OniRecording(const fs::path& file, OpenNiCamera& camera, const SensorInfo& sensor)
    : impl_(std::make_unique<Impl>()) {
  impl_->camera = &camera;
  impl_->file = file;
  if (fs::exists(file)) throw InputError(file, "exists; choose a new file name");
  io::WriteSensorJson(fs::path(file.string() + ".sensor.json"), sensor);
  impl_->sidecar.open(file.string() + ".exposure.txt");
  if (!impl_->sidecar) throw InputError(file.string() + ".exposure.txt", "cannot be opened for writing");
  // The player renumbers frames and rebases timestamps, so frames are known by their
  // content: a fingerprint of the colour image (the recording is lossless).
  impl_->sidecar << "# colour fingerprint (FNV-1a 64, hex), exposure_ms, gain, device frame number; frames not "
                    "listed: exposure unknown\n";
  camera.StartOniRecording(file.string());
}

OniRecording::~OniRecording() { Stop(); }

void OniRecording::NoteFrame(const LiveFrame& f, std::optional<double> exposure_ms, std::optional<double> gain) {
  if (!exposure_ms || !impl_->sidecar.is_open()) return;
  impl_->sidecar << std::hex << Fingerprint(f.color) << std::dec << ' ' << *exposure_ms << ' ' << gain.value_or(1.0)
                 << ' ' << f.index << '\n';
  impl_->sidecar.flush();
  if (!impl_->sidecar) throw InputError(impl_->file.string() + ".exposure.txt", "write failed (disk full?)");
}

void OniRecording::Stop() {
  if (!impl_->camera) return;
  impl_->camera->StopOniRecording();
  impl_->sidecar.close();
  impl_->camera = nullptr;
}

// ---- .oni playback ---------------------------------------------------------------------------

struct OniPlaybackSource::Impl {
  fs::path file;
  openni::Device device;
  openni::VideoStream color, depth;
  SensorInfo sensor;
  std::map<std::uint64_t, std::pair<double, double>> exposures;  // fingerprint -> exposure_ms, gain
  int frames = 0, delivered = 0;
  std::optional<detail::FramePairer> pairer;
};

OniPlaybackSource::OniPlaybackSource(const fs::path& file) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.file = file;
  if (!fs::exists(file)) throw InputError(file, "recording not found");
  CheckInputFile(file, std::uintmax_t(1) << 40, "a recording");
  const fs::path sensor_file = file.string() + ".sensor.json";
  if (fs::exists(sensor_file)) {
    m.sensor = io::ReadSensorJson(sensor_file);
  } else {
    m.sensor = sim::BuiltinXtionProfile();
    m.sensor.warnings.push_back(Say(words::kRecordingProfileMissing, {sensor_file.string()}));
  }
  m.sensor.depth_scale = 1000.0;
  const fs::path exposure_file = file.string() + ".exposure.txt";
  if (fs::exists(exposure_file)) {
    std::istringstream in(ReadInputFile(exposure_file, kMaxTextBytes, "an exposure list"));
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      if (line.empty() || line[0] == '#') continue;
      std::istringstream ls(line);
      std::uint64_t key;
      double ms, gain;
      if (!(ls >> std::hex >> key >> std::dec >> ms >> gain) || !(ms > 0) || !(gain > 0))
        throw InputError(exposure_file, number, "expected 'fingerprint exposure_ms gain [device_frame]'");
      m.exposures[key] = {ms, gain};
    }
  } else {
    m.sensor.warnings.push_back(Say(words::kRecordingExposuresMissing, {exposure_file.string()}));
  }
  EnsureOpenNi();
  const std::string who = file.string();
  if (m.device.open(who.c_str()) != openni::STATUS_OK)
    throw InputError(file, std::string("cannot be opened as an OpenNI2 recording: ") + openni::OpenNI::getExtendedError());
  openni::PlaybackControl* pc = m.device.getPlaybackControl();
  if (!pc) throw InputError(file, "is not an OpenNI2 recording");
  // Step frame by frame (seeking crashes Debian's player): manual speed, no repeat.
  pc->setSpeed(-1);
  pc->setRepeatEnabled(false);
  for (auto [stream, type, name] : {std::tuple{&m.color, openni::SENSOR_COLOR, "colour"},
                                    std::tuple{&m.depth, openni::SENSOR_DEPTH, "depth"}}) {
    if (!m.device.hasSensor(type) || stream->create(m.device, type) != openni::STATUS_OK)
      throw InputError(file, std::string("has no ") + name + " stream");
  }
  const openni::VideoMode cm = m.color.getVideoMode(), dm = m.depth.getVideoMode();
  if (cm.getPixelFormat() != openni::PIXEL_FORMAT_RGB888)
    throw InputError(file, "colour stream is not RGB888");
  if (dm.getPixelFormat() != openni::PIXEL_FORMAT_DEPTH_1_MM)
    throw InputError(file, "depth stream is not in millimetres (DEPTH_1_MM)");
  if (cm.getResolutionX() != dm.getResolutionX() || cm.getResolutionY() != dm.getResolutionY())
    throw InputError(file, "colour and depth differ in size");
  if (cm.getResolutionX() != m.sensor.camera.width || cm.getResolutionY() != m.sensor.camera.height)
    throw InputError(file, "frames are " + std::to_string(cm.getResolutionX()) + "x" + std::to_string(cm.getResolutionY()) +
                               " but its sensor profile says " + std::to_string(m.sensor.camera.width) + "x" +
                               std::to_string(m.sensor.camera.height));
  m.pairer.emplace(cm.getFps());
  m.frames = pc->getNumberOfFrames(m.color);
  if (m.color.start() != openni::STATUS_OK || m.depth.start() != openni::STATUS_OK)
    throw InputError(file, std::string("streams would not start: ") + openni::OpenNI::getExtendedError());
}

OniPlaybackSource::~OniPlaybackSource() {
  // The device is closed before its streams are destroyed: closing joins Debian's player
  // thread, which crashed now and then (1 in 6-12 closes on a loaded machine) when the
  // streams it delivers to were already gone; in this order, 40 of 40 under the same load.
  impl_->color.stop();
  impl_->depth.stop();
  impl_->device.close();
  impl_->color.destroy();
  impl_->depth.destroy();
}

int OniPlaybackSource::size() const { return impl_->frames; }
const SensorInfo& OniPlaybackSource::sensor() const { return impl_->sensor; }
std::string OniPlaybackSource::description() const { return "OpenNI2 recording " + impl_->file.string(); }

bool OniPlaybackSource::Next(pipeline::FrameInput& frame) {
  Impl& m = *impl_;
  while (m.delivered + m.pairer->unpaired_color() < m.frames) {
    if (std::optional<LiveFrame> f = m.pairer->Pop()) {
      ++m.delivered;
      std::optional<double> exposure, gain;
      if (auto it = m.exposures.find(Fingerprint(f->color)); it != m.exposures.end())
        exposure = it->second.first, gain = it->second.second;
      frame = ToInput(*f, m.sensor.depth_scale, exposure, gain);
      return true;
    }
    openni::VideoStream* streams[2] = {&m.color, &m.depth};
    int ready = -1;
    if (openni::OpenNI::waitForAnyStream(streams, 2, &ready, 2000) != openni::STATUS_OK) return false;  // end
    openni::VideoFrameRef ref;
    if (streams[ready]->readFrame(&ref) != openni::STATUS_OK || !ref.isValid()) return false;
    if (ready == 0)
      m.pairer->AddColor(detail::CopyFrame(ref));
    else
      m.pairer->AddDepth(detail::CopyFrame(ref));
  }
  return false;
}

// ---- every source ------------------------------------------------------------------------------

std::unique_ptr<pipeline::FrameSource> OpenAnySource(const std::string& spec, const std::string& response) {
  if (IsLiveSpec(spec)) return std::make_unique<LiveFrameSource>(ParseLiveSpec(spec));
  if (fs::path(spec).extension() == ".oni") return std::make_unique<OniPlaybackSource>(spec);
  return io::OpenSource(spec, response);
}

}  // namespace hdrf::sensors
