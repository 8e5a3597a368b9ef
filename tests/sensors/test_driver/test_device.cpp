// The test OpenNI2 driver: the project's synthetic sensor served as an OpenNI2 device, so
// that every part of live capture (listing, streaming, exposure control, hot plug, .oni
// recording and playback) is tested on machines without a camera. Built with the tests as
// libHdrfTestDevice.so.0 and loaded from a private driver folder (tests/sensors/README.md).
//
// The device:
//   URI "hdrf-test://0", serial $HDRF_TEST_DEVICE_SERIAL (default HDRF-SIM-0001)
//   colour RGB888 and depth DEPTH_1_MM, 640x480 and 320x240 at 30 Hz, depth registered to
//   colour (the scene is rendered from the colour camera), mirroring on until switched off
//   (as shipped cameras do)
//   colour properties: auto exposure, auto white balance, exposure (raw unit 0.1 ms),
//   gain (100 = unity), video mode, cropping (off only), mirroring, fields of view
//   hot plug: the file named by $HDRF_TEST_DEVICE_CONTROL, polled every 10 ms; "unplugged"
//   disconnects the device (frames stop, OpenNI reports the disconnect), "plugged"
//   connects it again; a device closed while unplugged goes on along its path where it
//   stopped when it is opened again (the operator held the camera still), so a scan that
//   resumes after a replug can keep tracking
//   further words in the control file: "still" holds the camera where it is (a camera on a
//   tripod, for exposure sweeps; without it the camera moves on), "light=F" scales the
//   scene's radiance by F (light=1000: a scene saturated at every exposure)
// $HDRF_TEST_DEVICE_FRAMES_PER_VIEW (default 1) slows the camera down: each view is held for
// that many frames (a scan slower than 30 Hz then still sees small steps).
// The camera moves back and forth along 48 views of the room's handheld path (rendered
// once per resolution, then only exposed per frame, so VGA keeps 30 Hz on two cores).
#define XN_NEW(type, arg) new type(arg)
#define XN_DELETE(p) delete (p)
#include <Driver/OniDriverAPI.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "sim/auto_exposure.h"
#include "sim/noise.h"
#include "sim/synthetic_source.h"

namespace {

using namespace std::chrono_literals;
constexpr int kViews = 48;
constexpr double kUnitMs = 0.1;  // raw exposure unit
constexpr const char* kUri = "hdrf-test://0";

std::string Env(const char* name, const char* fallback);

// Set from the control file by the driver's watcher.
std::atomic<bool> g_still{false};
std::atomic<float> g_light{1.f};

int FramesPerView() {
  static const int n = std::max(1, std::atoi(Env("HDRF_TEST_DEVICE_FRAMES_PER_VIEW", "1").c_str()));
  return n;
}

std::string Env(const char* name, const char* fallback) {
  const char* v = std::getenv(name);
  return v && *v ? v : fallback;
}

// Views of the path, per resolution, rendered on first use and kept for the process.
struct View {
  hdrf::RadianceImage radiance;
  hdrf::DepthRawImage depth_mm;
};
class ViewCache {
 public:
  const View& Get(int w, int h, int i) {
    std::lock_guard lock(mutex_);
    auto& entry = cache_[{w, h}];
    if (!entry.source) {
      hdrf::sim::SimOptions o;
      o.width = w;
      o.height = h;
      o.frames = kViews;
      o.depth_scale = 1000.0;  // DEPTH_1_MM
      entry.source = std::make_unique<hdrf::sim::SyntheticSource>(o);
      entry.views.resize(kViews);
    }
    View& v = entry.views[std::size_t(i)];
    if (v.radiance.empty()) {
      hdrf::sim::SimFrame f = entry.source->RenderView(i);
      v.radiance = std::move(f.radiance);
      v.depth_mm = std::move(f.depth);
    }
    return v;
  }
  const hdrf::sim::SyntheticSource& Source(int w, int h) {
    Get(w, h, 0);
    std::lock_guard lock(mutex_);
    return *cache_[{w, h}].source;
  }

 private:
  struct Entry {
    std::unique_ptr<hdrf::sim::SyntheticSource> source;
    std::vector<View> views;
  };
  std::mutex mutex_;
  std::map<std::pair<int, int>, Entry> cache_;
};
ViewCache& Views() {
  static ViewCache cache;
  return cache;
}

OniVideoMode Mode(OniPixelFormat f, int w, int h) { return {f, w, h, 30}; }

class TestDevice;

class TestStream : public oni::driver::StreamBase {
 public:
  TestStream(TestDevice* device, OniSensorType type) : device_(device), type_(type) {
    mode_ = Mode(type == ONI_SENSOR_COLOR ? ONI_PIXEL_FORMAT_RGB888 : ONI_PIXEL_FORMAT_DEPTH_1_MM, 640, 480);
  }
  OniStatus start() override;
  void stop() override;
  bool started() const { return started_; }
  OniSensorType type() const { return type_; }

  OniBool isPropertySupported(int id) override {
    switch (id) {
      case ONI_STREAM_PROPERTY_VIDEO_MODE: case ONI_STREAM_PROPERTY_CROPPING:
      case ONI_STREAM_PROPERTY_MIRRORING: case ONI_STREAM_PROPERTY_HORIZONTAL_FOV:
      case ONI_STREAM_PROPERTY_VERTICAL_FOV: case ONI_STREAM_PROPERTY_STRIDE:
        return true;
      case ONI_STREAM_PROPERTY_MAX_VALUE: case ONI_STREAM_PROPERTY_MIN_VALUE:
        return type_ == ONI_SENSOR_DEPTH;
      case ONI_STREAM_PROPERTY_AUTO_EXPOSURE: case ONI_STREAM_PROPERTY_AUTO_WHITE_BALANCE:
      case ONI_STREAM_PROPERTY_EXPOSURE: case ONI_STREAM_PROPERTY_GAIN:
        return type_ == ONI_SENSOR_COLOR;
      default:
        return false;
    }
  }

  template <class T>
  static OniStatus Put(const T& value, void* data, int* size) {
    if (*size < int(sizeof(T))) return ONI_STATUS_BAD_PARAMETER;
    std::memcpy(data, &value, sizeof(T));
    *size = int(sizeof(T));
    return ONI_STATUS_OK;
  }
  template <class T>
  static bool Take(const void* data, int size, T* out) {
    if (size != int(sizeof(T))) return false;
    std::memcpy(out, data, sizeof(T));
    return true;
  }

  OniStatus getProperty(int id, void* data, int* size) override {
    std::lock_guard lock(mutex_);
    const hdrf::PinholeCamera cam = hdrf::sim::SimCamera(mode_.resolutionX, mode_.resolutionY);
    switch (id) {
      case ONI_STREAM_PROPERTY_VIDEO_MODE: return Put(mode_, data, size);
      case ONI_STREAM_PROPERTY_CROPPING: return Put(OniCropping{0, 0, 0, mode_.resolutionX, mode_.resolutionY}, data, size);
      case ONI_STREAM_PROPERTY_MIRRORING: return Put(OniBool(mirror_), data, size);
      case ONI_STREAM_PROPERTY_HORIZONTAL_FOV:
        return Put(float(2 * std::atan(0.5 * mode_.resolutionX / cam.fx)), data, size);
      case ONI_STREAM_PROPERTY_VERTICAL_FOV:
        return Put(float(2 * std::atan(0.5 * mode_.resolutionY / cam.fy)), data, size);
      case ONI_STREAM_PROPERTY_STRIDE:
        return Put(int(mode_.resolutionX * (type_ == ONI_SENSOR_COLOR ? 3 : 2)), data, size);
      case ONI_STREAM_PROPERTY_MAX_VALUE: if (type_ == ONI_SENSOR_DEPTH) return Put(int(10000), data, size); break;
      case ONI_STREAM_PROPERTY_MIN_VALUE: if (type_ == ONI_SENSOR_DEPTH) return Put(int(0), data, size); break;
      case ONI_STREAM_PROPERTY_AUTO_EXPOSURE: if (type_ == ONI_SENSOR_COLOR) return Put(OniBool(ae_), data, size); break;
      case ONI_STREAM_PROPERTY_AUTO_WHITE_BALANCE: if (type_ == ONI_SENSOR_COLOR) return Put(OniBool(awb_), data, size); break;
      case ONI_STREAM_PROPERTY_EXPOSURE: if (type_ == ONI_SENSOR_COLOR) return Put(int(exposure_raw_), data, size); break;
      case ONI_STREAM_PROPERTY_GAIN: if (type_ == ONI_SENSOR_COLOR) return Put(int(gain_), data, size); break;
      default: break;
    }
    return ONI_STATUS_NOT_SUPPORTED;
  }

  OniStatus setProperty(int id, const void* data, int size) override {
    std::lock_guard lock(mutex_);
    switch (id) {
      case ONI_STREAM_PROPERTY_VIDEO_MODE: {
        OniVideoMode m;
        if (!Take(data, size, &m)) return ONI_STATUS_BAD_PARAMETER;
        const OniPixelFormat want = type_ == ONI_SENSOR_COLOR ? ONI_PIXEL_FORMAT_RGB888 : ONI_PIXEL_FORMAT_DEPTH_1_MM;
        const bool size_ok = (m.resolutionX == 640 && m.resolutionY == 480) || (m.resolutionX == 320 && m.resolutionY == 240);
        if (m.pixelFormat != want || !size_ok || m.fps != 30) return ONI_STATUS_NOT_SUPPORTED;
        if (started_) return ONI_STATUS_OUT_OF_FLOW;
        mode_ = m;
        return ONI_STATUS_OK;
      }
      case ONI_STREAM_PROPERTY_CROPPING: {
        OniCropping c;
        if (!Take(data, size, &c)) return ONI_STATUS_BAD_PARAMETER;
        return c.enabled ? ONI_STATUS_NOT_SUPPORTED : ONI_STATUS_OK;
      }
      case ONI_STREAM_PROPERTY_MIRRORING: {
        OniBool b;
        if (!Take(data, size, &b)) return ONI_STATUS_BAD_PARAMETER;
        mirror_ = b != 0;
        return ONI_STATUS_OK;
      }
      case ONI_STREAM_PROPERTY_AUTO_EXPOSURE: case ONI_STREAM_PROPERTY_AUTO_WHITE_BALANCE: {
        if (type_ != ONI_SENSOR_COLOR) break;
        OniBool b;
        if (!Take(data, size, &b)) return ONI_STATUS_BAD_PARAMETER;
        (id == ONI_STREAM_PROPERTY_AUTO_EXPOSURE ? ae_ : awb_) = b != 0;
        return ONI_STATUS_OK;
      }
      case ONI_STREAM_PROPERTY_EXPOSURE: case ONI_STREAM_PROPERTY_GAIN: {
        if (type_ != ONI_SENSOR_COLOR) break;
        int v;
        if (!Take(data, size, &v) || v <= 0 || v > 100000) return ONI_STATUS_BAD_PARAMETER;
        // Like the cameras this stands in for, a value set before the stream runs is lost.
        if (!started_) return ONI_STATUS_OK;
        (id == ONI_STREAM_PROPERTY_EXPOSURE ? exposure_raw_ : gain_) = v;
        return ONI_STATUS_OK;
      }
      default: break;
    }
    return ONI_STATUS_NOT_SUPPORTED;
  }

  // Called by the device's frame thread.
  // `index` numbers the frames; `position` is how far along the path the camera is.
  void Deliver(int index, int position, std::uint64_t timestamp_us, std::uint32_t seed,
               hdrf::sim::AutoExposure& ae, double& last_metered) {
    OniVideoMode mode;
    bool mirror, ae_on, awb_on;
    int exposure_raw, gain;
    {
      std::lock_guard lock(mutex_);
      mode = mode_;
      mirror = mirror_;
      ae_on = ae_;
      awb_on = awb_;
      exposure_raw = exposure_raw_;
      gain = gain_;
    }
    const int w = mode.resolutionX, h = mode.resolutionY;
    const int cycle = 2 * kViews - 2;
    const int phase = (position / FramesPerView()) % cycle;
    const int view_index = phase < kViews ? phase : cycle - phase;
    const View& view = Views().Get(w, h, view_index);
    OniFrame* frame = getServices().acquireFrame();
    if (!frame) return;
    frame->sensorType = type_;
    frame->timestamp = timestamp_us;
    frame->frameIndex = index + 1;
    frame->width = w;
    frame->height = h;
    frame->videoMode = mode;
    frame->croppingEnabled = false;
    frame->cropOriginX = frame->cropOriginY = 0;
    if (type_ == ONI_SENSOR_COLOR) {
      double exposure_ms = exposure_raw * kUnitMs;
      if (ae_on) {
        exposure_ms = ae.Next(index, last_metered);
        // What the device shows as its exposure while AE runs: the unit it chose.
        std::lock_guard lock(mutex_);
        exposure_raw_ = std::max(1, int(std::lround(exposure_ms / kUnitMs)));
      }
      last_metered = hdrf::sim::MeterCentre(view.radiance);
      hdrf::RadianceImage scaled = view.radiance.Clone();
      float g[3] = {1.f, 1.f, 1.f};
      if (awb_on) {  // grey world: equal channel means
        double sum[3] = {0, 0, 0};
        for (std::size_t k = 0; k < scaled.size(); ++k) {
          sum[0] += scaled[k].x; sum[1] += scaled[k].y; sum[2] += scaled[k].z;
        }
        const double mean = (sum[0] + sum[1] + sum[2]) / 3;
        for (int c = 0; c < 3; ++c) g[c] = float(std::clamp(mean / std::max(sum[c], 1e-9), 0.5, 2.0));
      }
      const float gf = float(gain) / 100.f * g_light.load();
      for (std::size_t k = 0; k < scaled.size(); ++k)
        scaled[k] = {scaled[k].x * g[0] * gf, scaled[k].y * g[1] * gf, scaled[k].z * g[2] * gf};
      const hdrf::ColorImage color =
          Views().Source(w, h).Expose(scaled, exposure_ms, hdrf::sim::Hash(seed, std::uint32_t(index)));
      frame->stride = w * 3;
      auto* out = static_cast<std::uint8_t*>(frame->data);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const hdrf::Rgb8 p = color(mirror ? w - 1 - x : x, y);
          std::uint8_t* o = out + (std::size_t(y) * w + x) * 3;
          o[0] = p.r; o[1] = p.g; o[2] = p.b;
        }
      frame->dataSize = w * h * 3;
    } else {
      frame->stride = w * 2;
      auto* out = static_cast<std::uint16_t*>(frame->data);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) out[std::size_t(y) * w + x] = view.depth_mm(mirror ? w - 1 - x : x, y);
      frame->dataSize = w * h * 2;
    }
    raiseNewFrame(frame);
    getServices().releaseFrame(frame);
  }

  int getRequiredFrameSize() override {
    std::lock_guard lock(mutex_);
    return mode_.resolutionX * mode_.resolutionY * (type_ == ONI_SENSOR_COLOR ? 3 : 2);
  }

 private:
  TestDevice* device_;
  OniSensorType type_;
  std::mutex mutex_;
  OniVideoMode mode_;
  bool mirror_ = true;
  bool ae_ = true, awb_ = true;
  int exposure_raw_ = 100, gain_ = 100;
  std::atomic<bool> started_{false};
};

class TestDevice : public oni::driver::DeviceBase {
 public:
  TestDevice(std::string serial, std::atomic<bool>* plugged, std::atomic<int>* resume)
      : serial_(std::move(serial)), plugged_(plugged), resume_(resume) {
    color_modes_ = {Mode(ONI_PIXEL_FORMAT_RGB888, 640, 480), Mode(ONI_PIXEL_FORMAT_RGB888, 320, 240)};
    depth_modes_ = {Mode(ONI_PIXEL_FORMAT_DEPTH_1_MM, 640, 480), Mode(ONI_PIXEL_FORMAT_DEPTH_1_MM, 320, 240)};
    sensors_[0] = {ONI_SENSOR_COLOR, int(color_modes_.size()), color_modes_.data()};
    sensors_[1] = {ONI_SENSOR_DEPTH, int(depth_modes_.size()), depth_modes_.data()};
  }
  ~TestDevice() override {
    StopThread();
    if (!plugged_->load() && delivered_ >= 0) resume_->store(delivered_ + 1);
  }

  OniStatus getSensorInfoList(OniSensorInfo** infos, int* count) override {
    *infos = sensors_;
    *count = 2;
    return ONI_STATUS_OK;
  }
  oni::driver::StreamBase* createStream(OniSensorType type) override {
    if (type != ONI_SENSOR_COLOR && type != ONI_SENSOR_DEPTH) return nullptr;
    std::lock_guard lock(mutex_);
    auto* s = new TestStream(this, type);
    streams_.push_back(s);
    return s;
  }
  void destroyStream(oni::driver::StreamBase* stream) override {
    {
      std::lock_guard lock(mutex_);
      streams_.erase(std::remove(streams_.begin(), streams_.end(), stream), streams_.end());
    }
    delete stream;
  }
  OniBool isPropertySupported(int id) override {
    return id == ONI_DEVICE_PROPERTY_SERIAL_NUMBER || id == ONI_DEVICE_PROPERTY_IMAGE_REGISTRATION ||
           id == ONI_DEVICE_PROPERTY_FIRMWARE_VERSION || id == ONI_DEVICE_PROPERTY_HARDWARE_VERSION;
  }
  OniStatus getProperty(int id, void* data, int* size) override {
    switch (id) {
      case ONI_DEVICE_PROPERTY_SERIAL_NUMBER:
      case ONI_DEVICE_PROPERTY_FIRMWARE_VERSION: {
        const std::string v = id == ONI_DEVICE_PROPERTY_SERIAL_NUMBER ? serial_ : "hdrf-test-1";
        if (*size < int(v.size()) + 1) return ONI_STATUS_BAD_PARAMETER;
        std::memcpy(data, v.c_str(), v.size() + 1);
        *size = int(v.size()) + 1;
        return ONI_STATUS_OK;
      }
      case ONI_DEVICE_PROPERTY_HARDWARE_VERSION: return TestStream::Put(int(1), data, size);
      case ONI_DEVICE_PROPERTY_IMAGE_REGISTRATION: return TestStream::Put(registration_, data, size);
      default: return ONI_STATUS_NOT_SUPPORTED;
    }
  }
  OniStatus setProperty(int id, const void* data, int size) override {
    if (id != ONI_DEVICE_PROPERTY_IMAGE_REGISTRATION) return ONI_STATUS_NOT_SUPPORTED;
    return TestStream::Take(data, size, &registration_) ? ONI_STATUS_OK : ONI_STATUS_BAD_PARAMETER;
  }
  OniBool isImageRegistrationModeSupported(OniImageRegistrationMode) override { return true; }

  void StreamStarted() {
    std::lock_guard lock(mutex_);
    if (thread_.joinable()) return;
    running_ = true;
    thread_ = std::thread([this] { Run(); });
  }
  void StreamStopped() {
    bool any;
    {
      std::lock_guard lock(mutex_);
      any = std::any_of(streams_.begin(), streams_.end(), [](TestStream* s) { return s->started(); });
    }
    if (!any) StopThread();
  }

 private:
  void StopThread() {
    running_ = false;
    if (thread_.joinable() && thread_.get_id() != std::this_thread::get_id()) thread_.join();
  }
  void Run() {
    const std::uint32_t seed = 1;
    hdrf::sim::AutoExposure ae(hdrf::sim::AeOptions{}, seed);
    double metered = -1;
    // Render the path's views before the first frame, so the stream keeps its rate.
    std::vector<std::pair<int, int>> sizes;
    {
      std::lock_guard lock(mutex_);
      for (TestStream* s : streams_) {
        OniVideoMode m;
        int size = sizeof m;
        s->getProperty(ONI_STREAM_PROPERTY_VIDEO_MODE, &m, &size);
        sizes.push_back({m.resolutionX, m.resolutionY});
      }
    }
    for (auto [w, h] : sizes)
      for (int i = 0; i < kViews && running_; ++i) Views().Get(w, h, i);
    const auto t0 = std::chrono::steady_clock::now();
    const int first = resume_->exchange(0);
    int position = first;
    for (int index = first; running_; ++index) {
      std::this_thread::sleep_until(t0 + std::chrono::microseconds(std::int64_t(index - first) * 33333));
      if (!plugged_->load()) continue;  // unplugged: no frames
      std::vector<TestStream*> live;
      {
        std::lock_guard lock(mutex_);
        for (TestStream* s : streams_)
          if (s->started()) live.push_back(s);
      }
      const std::uint64_t ts = std::uint64_t(index) * 33333u;
      // Colour first: auto exposure meters it; depth follows with the same timestamp.
      std::sort(live.begin(), live.end(), [](TestStream* a, TestStream* b) { return a->type() < b->type(); });
      for (TestStream* s : live) s->Deliver(index, position, ts, seed, ae, metered);
      delivered_ = position;
      if (!g_still.load()) ++position;
    }
  }

  std::string serial_;
  std::atomic<bool>* plugged_;
  std::atomic<int>* resume_;      // where the next device starts along the path
  std::atomic<int> delivered_{-1};
  std::vector<OniVideoMode> color_modes_, depth_modes_;
  OniSensorInfo sensors_[2];
  std::mutex mutex_;
  std::vector<TestStream*> streams_;
  OniImageRegistrationMode registration_ = ONI_IMAGE_REGISTRATION_OFF;
  std::thread thread_;
  std::atomic<bool> running_{false};
};

OniStatus TestStream::start() {
  started_ = true;
  device_->StreamStarted();
  return ONI_STATUS_OK;
}
void TestStream::stop() {
  started_ = false;
  device_->StreamStopped();
}

class TestDriver : public oni::driver::DriverBase {
 public:
  explicit TestDriver(OniDriverServices* services) : DriverBase(services) {
    std::memset(&info_, 0, sizeof info_);
    std::strncpy(info_.uri, kUri, ONI_MAX_STR - 1);
    std::strncpy(info_.vendor, "HDRFusion", ONI_MAX_STR - 1);
    std::strncpy(info_.name, "Synthetic RGB-D (test driver)", ONI_MAX_STR - 1);
    info_.usbVendorId = 0x1d27;
    info_.usbProductId = 0xff01;
    serial_ = Env("HDRF_TEST_DEVICE_SERIAL", "HDRF-SIM-0001");
    control_ = Env("HDRF_TEST_DEVICE_CONTROL", "");
  }
  OniStatus initialize(oni::driver::DeviceConnectedCallback connected,
                       oni::driver::DeviceDisconnectedCallback disconnected,
                       oni::driver::DeviceStateChangedCallback state, void* cookie) override {
    DriverBase::initialize(connected, disconnected, state, cookie);
    plugged_ = ControlSays() != "unplugged";
    if (plugged_) deviceConnected(&info_);
    if (!control_.empty()) {
      watching_ = true;
      watcher_ = std::thread([this] { Watch(); });
    }
    return ONI_STATUS_OK;
  }
  oni::driver::DeviceBase* deviceOpen(const char* uri, const char* /*mode*/) override {
    if (std::strcmp(uri, kUri) != 0 || !plugged_) return nullptr;
    return new TestDevice(serial_, &plugged_, &resume_);
  }
  void deviceClose(oni::driver::DeviceBase* device) override { delete device; }
  OniStatus tryDevice(const char* uri) override {
    return std::strcmp(uri, kUri) == 0 && plugged_ ? ONI_STATUS_OK : ONI_STATUS_ERROR;
  }
  void shutdown() override {
    watching_ = false;
    if (watcher_.joinable()) watcher_.join();
  }
  void* enableFrameSync(oni::driver::StreamBase**, int) override { return this; }  // frames share timestamps
  void disableFrameSync(void*) override {}

 private:
  // The first word (plugged, unplugged); the others set the scene ("still", "light=F").
  std::string ControlSays() const {
    if (control_.empty()) return "";
    std::ifstream in(control_);
    std::string word, more;
    in >> word;
    bool still = false;
    float light = 1.f;
    while (in >> more) {
      if (more == "still") still = true;
      else if (more.rfind("light=", 0) == 0) light = std::strtof(more.c_str() + 6, nullptr);
    }
    g_still = still;
    g_light = light > 0 ? light : 1.f;
    return word;
  }
  void Watch() {
    while (watching_) {
      std::this_thread::sleep_for(10ms);
      const std::string word = ControlSays();
      if (word == "unplugged" && plugged_) {
        plugged_ = false;
        deviceDisconnected(&info_);
      } else if (word == "plugged" && !plugged_) {
        plugged_ = true;
        deviceConnected(&info_);
      }
    }
  }

  OniDeviceInfo info_;
  std::string serial_, control_;
  std::atomic<bool> plugged_{true};
  std::atomic<int> resume_{0};
  std::atomic<bool> watching_{false};
  std::thread watcher_;
};

}  // namespace

ONI_EXPORT_DRIVER(TestDriver)
