#include "sensors/openni_camera.h"

#include "sensors/frame_pairing.h"

#include <OpenNI.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <thread>

namespace hdrf::sensors {

namespace {

using namespace std::chrono_literals;

}  // namespace

void EnsureOpenNi() {
  static std::once_flag once;
  static std::string failure;
  std::call_once(once, [] {
    if (openni::OpenNI::initialize() != openni::STATUS_OK)
      failure = std::string("OpenNI2 could not be initialised: ") + openni::OpenNI::getExtendedError();
  });
  if (!failure.empty()) throw SensorError(failure);
}

namespace {

std::string Serial(openni::Device& device) {
  char buf[ONI_MAX_STR] = {0};
  int size = sizeof buf;
  if (device.getProperty(ONI_DEVICE_PROPERTY_SERIAL_NUMBER, buf, &size) != openni::STATUS_OK) return "";
  buf[sizeof buf - 1] = 0;
  return buf;
}

std::string Describe(const DeviceEntry& e) {
  return "'" + e.name + "' (" + e.uri + (e.serial.empty() ? "" : ", serial " + e.serial) + ")";
}

}  // namespace

CaptureMode ParseCaptureMode(const std::string& name) {
  if (name == "vga") return {640, 480, 30};
  if (name == "qvga") return {320, 240, 30};
  throw SettingError("mode", "unknown capture mode '" + name + "'; choose vga (640x480) or qvga (320x240)");
}

std::vector<DeviceEntry> ListDevices(const std::vector<DeviceEntry>& known) {
  EnsureOpenNi();
  openni::Array<openni::DeviceInfo> infos;
  openni::OpenNI::enumerateDevices(&infos);
  std::vector<DeviceEntry> out;
  for (int i = 0; i < infos.getSize(); ++i) {
    DeviceEntry e{infos[i].getName(), infos[i].getVendor(), infos[i].getUri(), ""};
    const auto open = std::find_if(known.begin(), known.end(), [&](const DeviceEntry& k) { return k.uri == e.uri; });
    if (open != known.end()) {
      out.push_back(*open);
      continue;
    }
    openni::Device d;
    if (d.open(e.uri.c_str()) == openni::STATUS_OK) {
      e.serial = Serial(d);
      d.close();
    }
    out.push_back(e);
  }
  return out;
}

// ---- hot plug ----------------------------------------------------------------------------

struct HotplugMonitor::Impl : openni::OpenNI::DeviceConnectedListener,
                              openni::OpenNI::DeviceDisconnectedListener {
  Callback callback;
  void onDeviceConnected(const openni::DeviceInfo* info) override { callback(info->getUri(), true); }
  void onDeviceDisconnected(const openni::DeviceInfo* info) override { callback(info->getUri(), false); }
};

HotplugMonitor::HotplugMonitor(Callback callback) : impl_(std::make_unique<Impl>()) {
  EnsureOpenNi();
  impl_->callback = std::move(callback);
  openni::OpenNI::addDeviceConnectedListener(impl_.get());
  openni::OpenNI::addDeviceDisconnectedListener(impl_.get());
}

HotplugMonitor::~HotplugMonitor() {
  openni::OpenNI::removeDeviceConnectedListener(impl_.get());
  openni::OpenNI::removeDeviceDisconnectedListener(impl_.get());
}

// ---- the camera ----------------------------------------------------------------------------

struct OpenNiCamera::Impl : openni::OpenNI::DeviceDisconnectedListener {
  // OpenNI's frame listener serves one stream: one per stream, both feeding this.
  struct Listener : openni::VideoStream::NewFrameListener {
    Impl* owner = nullptr;
    void onNewFrame(openni::VideoStream& stream) override { owner->OnFrame(stream); }
  };
  Listener color_listener, depth_listener;

  static constexpr std::size_t kQueue = 8;

  DeviceEntry entry;
  CaptureMode mode;
  openni::Device device;
  openni::VideoStream color, depth;
  openni::Recorder recorder;
  bool registered = false;

  mutable std::mutex mutex;
  std::condition_variable arrived;
  std::optional<detail::FramePairer> pairer;
  std::deque<LiveFrame> queue;
  long arrivals = 0;        // paired frames produced
  long dropped = 0;         // besides the pairer's unpaired colour frames
  int last_color_index = -1;
  bool lost = false;
  // The exposure in force, once verified with AE off; frames arriving while a change is
  // settling carry none.
  std::optional<int> tag_exposure, tag_gain;

  void onDeviceDisconnected(const openni::DeviceInfo* info) override {
    if (entry.uri != info->getUri()) return;
    std::lock_guard lock(mutex);
    lost = true;
    arrived.notify_all();
  }

  void OnFrame(openni::VideoStream& stream) {
    openni::VideoFrameRef ref;
    if (stream.readFrame(&ref) != openni::STATUS_OK || !ref.isValid()) return;
    const bool is_color = ref.getSensorType() == openni::SENSOR_COLOR;
    if (is_color && ref.getVideoMode().getPixelFormat() != openni::PIXEL_FORMAT_RGB888) return;
    LiveFrame f = detail::CopyFrame(ref);
    std::lock_guard lock(mutex);
    if (is_color) {
      if (last_color_index >= 0 && f.index > last_color_index + 1) dropped += f.index - last_color_index - 1;
      last_color_index = f.index;
      f.exposure_raw = tag_exposure;
      f.gain = tag_gain;
      pairer->AddColor(std::move(f));
    } else {
      pairer->AddDepth(std::move(f));
    }
    while (std::optional<LiveFrame> pair = pairer->Pop()) {
      if (queue.size() >= kQueue) {
        queue.pop_front();
        ++dropped;
      }
      queue.push_back(std::move(*pair));
      ++arrivals;
      arrived.notify_all();
    }
  }

  // Waits until `n` more paired frames arrived (false on timeout or loss).
  bool WaitFrames(long n, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex);
    const long target = arrivals + n;
    return arrived.wait_for(lock, timeout, [&] { return arrivals >= target || lost; }) && !lost;
  }

  openni::CameraSettings* Settings() {
    openni::CameraSettings* s = color.getCameraSettings();
    if (!s || !s->isValid())
      throw SensorError("device " + Describe(entry) + " has no camera settings: exposure, gain, auto "
                        "exposure and white balance cannot be controlled");
    return s;
  }

  // Apply, let frames pass under the new value, read back; once more if the device did
  // not take it (devices drop values set while they reconfigure).
  template <class Set, class Get>
  void ApplyVerified(const std::string& what, Set set, Get get) {
    {
      std::lock_guard lock(mutex);
      tag_exposure.reset();
      tag_gain.reset();
    }
    for (int attempt = 0; attempt < 3; ++attempt) {
      set();
      if (!WaitFrames(2, 3000ms))
        throw SensorError("device " + Describe(entry) + " sent no frames after setting " + what);
      if (get()) {
        RetagExposure();
        return;
      }
    }
    throw SensorError("device " + Describe(entry) + " did not take " + what + " (read back differs)");
  }

  void RetagExposure() {
    openni::CameraSettings* s = color.getCameraSettings();
    std::lock_guard lock(mutex);
    tag_exposure.reset();
    tag_gain.reset();
    if (s && s->isValid() && !s->getAutoExposureEnabled()) {
      tag_exposure = s->getExposure();
      tag_gain = s->getGain();
    }
  }
};

OpenNiCamera::OpenNiCamera() : impl_(std::make_unique<Impl>()) {}

OpenNiCamera::~OpenNiCamera() {
  StopOniRecording();
  openni::OpenNI::removeDeviceDisconnectedListener(impl_.get());
  impl_->color.removeNewFrameListener(&impl_->color_listener);
  impl_->depth.removeNewFrameListener(&impl_->depth_listener);
  impl_->color.stop();
  impl_->depth.stop();
  impl_->color.destroy();
  impl_->depth.destroy();
  impl_->device.close();
}

std::unique_ptr<OpenNiCamera> OpenNiCamera::Open(const std::string& id, CaptureMode mode) {
  const std::vector<DeviceEntry> devices = ListDevices();
  if (devices.empty())
    throw SensorError("no OpenNI2 device is connected (check the cable, and that your user is in the "
                      "'video' group for the udev rules)");
  const DeviceEntry* found = nullptr;
  for (const DeviceEntry& e : devices)
    if (id.empty() || e.uri == id || (!e.serial.empty() && e.serial == id)) {
      found = &e;
      break;
    }
  if (!found) {
    std::string list;
    for (const DeviceEntry& e : devices) list += "\n  " + Describe(e);
    throw SensorError("no connected device has the URI or serial '" + id + "'; connected:" + list);
  }
  std::unique_ptr<OpenNiCamera> cam(new OpenNiCamera());
  Impl& m = *cam->impl_;
  m.entry = *found;
  m.mode = mode;
  m.pairer.emplace(mode.fps);
  const std::string who = "device " + Describe(m.entry);
  if (m.device.open(m.entry.uri.c_str()) != openni::STATUS_OK)
    throw SensorError(who + " could not be opened: " + openni::OpenNI::getExtendedError());
  if (m.entry.serial.empty()) m.entry.serial = Serial(m.device);

  auto start = [&](openni::VideoStream& s, openni::SensorType type, openni::PixelFormat format,
                   const char* name) {
    if (!m.device.hasSensor(type)) throw SensorError(who + " has no " + std::string(name) + " sensor");
    if (s.create(m.device, type) != openni::STATUS_OK)
      throw SensorError(who + ": the " + std::string(name) + " stream could not be created: " +
                        openni::OpenNI::getExtendedError());
    openni::VideoMode vm;
    vm.setResolution(mode.width, mode.height);
    vm.setFps(mode.fps);
    vm.setPixelFormat(format);
    if (s.setVideoMode(vm) != openni::STATUS_OK)
      throw SensorError(who + " does not offer " + std::string(name) + " at " + std::to_string(mode.width) + "x" +
                        std::to_string(mode.height) + " " + std::to_string(mode.fps) + " Hz");
    s.setMirroringEnabled(false);
    if (s.getMirroringEnabled())
      throw SensorError(who + ": the " + std::string(name) + " stream cannot switch mirroring off");
  };
  start(m.color, openni::SENSOR_COLOR, openni::PIXEL_FORMAT_RGB888, "colour");
  start(m.depth, openni::SENSOR_DEPTH, openni::PIXEL_FORMAT_DEPTH_1_MM, "depth");
  if (m.device.isImageRegistrationModeSupported(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR))
    m.registered = m.device.setImageRegistrationMode(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR) == openni::STATUS_OK;
  m.device.setDepthColorSyncEnabled(true);
  openni::OpenNI::addDeviceDisconnectedListener(&m);
  m.color_listener.owner = m.depth_listener.owner = &m;
  m.color.addNewFrameListener(&m.color_listener);
  m.depth.addNewFrameListener(&m.depth_listener);
  if (m.depth.start() != openni::STATUS_OK || m.color.start() != openni::STATUS_OK)
    throw SensorError(who + ": streams would not start: " + openni::OpenNI::getExtendedError());
  // Cameras take a moment to deliver their first frames (the test driver renders its views).
  if (!m.WaitFrames(1, 15s)) throw SensorError(who + " started its streams but sent no frame within 15 s");
  return cam;
}

const DeviceEntry& OpenNiCamera::entry() const { return impl_->entry; }
CaptureMode OpenNiCamera::mode() const { return impl_->mode; }
bool OpenNiCamera::depth_registered_by_device() const { return impl_->registered; }

bool OpenNiCamera::has_camera_settings() const {
  openni::CameraSettings* s = impl_->color.getCameraSettings();
  return s && s->isValid();
}

void OpenNiCamera::SetAutoExposure(bool on) {
  openni::CameraSettings* s = impl_->Settings();
  impl_->ApplyVerified(std::string("auto exposure ") + (on ? "on" : "off"),
                       [&] { s->setAutoExposureEnabled(on); }, [&] { return s->getAutoExposureEnabled() == on; });
}

void OpenNiCamera::SetAutoWhiteBalance(bool on) {
  openni::CameraSettings* s = impl_->Settings();
  impl_->ApplyVerified(std::string("auto white balance ") + (on ? "on" : "off"),
                       [&] { s->setAutoWhiteBalanceEnabled(on); },
                       [&] { return s->getAutoWhiteBalanceEnabled() == on; });
}

void OpenNiCamera::SetExposure(int raw) {
  if (raw <= 0) throw SettingError("exposure", "must be positive, got " + std::to_string(raw));
  openni::CameraSettings* s = impl_->Settings();
  if (s->getAutoExposureEnabled()) SetAutoExposure(false);  // a manual exposure needs AE off
  impl_->ApplyVerified("exposure " + std::to_string(raw), [&] { s->setExposure(raw); },
                       [&] { return s->getExposure() == raw; });
}

void OpenNiCamera::SetGain(int gain) {
  if (gain <= 0) throw SettingError("gain", "must be positive, got " + std::to_string(gain));
  openni::CameraSettings* s = impl_->Settings();
  impl_->ApplyVerified("gain " + std::to_string(gain), [&] { s->setGain(gain); },
                       [&] { return s->getGain() == gain; });
}

ExposureState OpenNiCamera::exposure() const {
  ExposureState st;
  openni::CameraSettings* s = impl_->color.getCameraSettings();
  if (!s || !s->isValid()) return st;
  st.auto_exposure = s->getAutoExposureEnabled();
  st.auto_white_balance = s->getAutoWhiteBalanceEnabled();
  st.exposure_raw = s->getExposure();
  st.gain = s->getGain();
  return st;
}

std::optional<LiveFrame> OpenNiCamera::Read(std::chrono::milliseconds timeout) {
  std::unique_lock lock(impl_->mutex);
  impl_->arrived.wait_for(lock, timeout, [&] { return !impl_->queue.empty() || impl_->lost; });
  if (impl_->queue.empty()) {
    if (impl_->lost) throw DeviceLost("device " + Describe(impl_->entry) + " was disconnected");
    return std::nullopt;
  }
  LiveFrame f = std::move(impl_->queue.front());
  impl_->queue.pop_front();
  return f;
}

long OpenNiCamera::dropped() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->dropped + impl_->pairer->unpaired_color();
}

void OpenNiCamera::Flush() {
  std::lock_guard lock(impl_->mutex);
  impl_->queue.clear();
}

bool OpenNiCamera::lost() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->lost;
}

void OpenNiCamera::StartOniRecording(const std::string& file) {
  Impl& m = *impl_;
  if (m.recorder.isValid()) throw SensorError("an .oni recording is already running");
  if (m.recorder.create(file.c_str()) != openni::STATUS_OK)
    throw SensorError(file + ": cannot create the .oni recording: " + openni::OpenNI::getExtendedError());
  if (m.recorder.attach(m.color, false) != openni::STATUS_OK || m.recorder.attach(m.depth, false) != openni::STATUS_OK ||
      m.recorder.start() != openni::STATUS_OK) {
    m.recorder.destroy();
    throw SensorError(file + ": cannot record the streams: " + openni::OpenNI::getExtendedError());
  }
  Flush();  // frames read from now on are in the recording
}

void OpenNiCamera::StopOniRecording() {
  if (!impl_->recorder.isValid()) return;
  impl_->recorder.stop();
  impl_->recorder.destroy();
}

}  // namespace hdrf::sensors
