// Live capture with the test OpenNI2 driver (the synthetic sensor as a device, loaded from a
// private driver folder; tests/sensors/CMakeLists.txt). Figures in docs/sensors.md.
#include <gtest/gtest.h>

#include <sys/mount.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <thread>

#include "io/sequence.h"
#include "io/sequence_source.h"
#include "pipeline/scan_session.h"
#include "radiometry/radiance.h"
#include "sensors/live_source.h"
#include "sensors/profiles.h"
#include "sensors/recorder.h"
#include "sim/builtin_sensor.h"
#include "sim/synthetic_source.h"
#include "support/test_support.h"
#include "test_device_control.h"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using namespace hdrf;
using namespace hdrf::sensors;

const std::string kSerial = "HDRF-SIM-0001";

// Set before OpenNI2 loads the driver (it reads them once): hot plug and profiles.
const test::TestDeviceControl g_env("hdrf_sensors", "plugged");

// The test device's own profile: the built-in response and its exposure unit (0.1 ms).
void SaveTestProfile() {
  SensorInfo s = sim::BuiltinXtionProfile();
  s.device = SensorInfo::Device{kSerial, "test device", 0.1};
  SaveProfile(kSerial, s);
}

// The view of the path a device frame shows (the driver goes back and forth over 48 views).
int ViewOf(int frame_index) {
  const int cycle = 2 * 48 - 2, phase = (frame_index - 1) % cycle;
  return phase < 48 ? phase : cycle - phase;
}

TEST(Sensors, ListsTheTestDevice) {
  const auto devices = ListDevices();
  ASSERT_EQ(devices.size(), 1u);
  EXPECT_EQ(devices[0].uri, "hdrf-test://0");
  EXPECT_EQ(devices[0].serial, kSerial);
  EXPECT_EQ(devices[0].vendor, "HDRFusion");
  // Opening by serial and by URI finds it; an unknown id lists what is connected.
  EXPECT_EQ(OpenNiCamera::Open(kSerial, ParseCaptureMode("qvga"))->entry().uri, "hdrf-test://0");
  try {
    OpenNiCamera::Open("NO-SUCH-SERIAL", {});
    FAIL() << "an unknown serial opened a device";
  } catch (const SensorError& e) {
    EXPECT_NE(std::string(e.what()).find("connected:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(kSerial), std::string::npos) << e.what();
  }
}

TEST(Sensors, Streams300VgaFramesWithNoneDropped) {
  auto cam = OpenNiCamera::Open("", ParseCaptureMode("vga"));
  EXPECT_TRUE(cam->depth_registered_by_device());
  // The device's depth, unmirrored and registered, is the simulator's depth of that view.
  sim::SimOptions so;
  so.width = 640;
  so.height = 480;
  so.frames = 48;
  so.depth_scale = 1000;
  const sim::SyntheticSource truth(so);
  int previous = -1, checked = 0;
  double first_ts = 0, last_ts = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int n = 0; n < 300; ++n) {
    std::optional<LiveFrame> f = cam->Read(2000ms);
    ASSERT_TRUE(f) << "no frame after " << n;
    ASSERT_EQ(f->color.width(), 640);
    ASSERT_EQ(f->depth_mm.width(), 640);
    if (previous >= 0) {
      EXPECT_EQ(f->index, previous + 1) << "frame numbers skip";
      EXPECT_NEAR(f->timestamp - last_ts, 1 / 30.0, 1e-3);
    } else {
      first_ts = f->timestamp;
    }
    previous = f->index;
    last_ts = f->timestamp;
    if (n % 50 == 0) {
      const DepthRawImage want = truth.RenderView(ViewOf(f->index)).depth;
      long same = 0;
      for (std::size_t k = 0; k < want.size(); ++k) same += want[k] == f->depth_mm[k];
      EXPECT_EQ(same, long(want.size())) << "depth differs from the scene's (mirrored?)";
      ++checked;
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(cam->dropped(), 0);
  EXPECT_EQ(checked, 6);
  std::printf("[ figures  ] 300 VGA frames: device clock %.3f s, wall %.3f s (%.1f frames/s), dropped %ld\n",
              last_ts - first_ts, wall, 300 / wall, cam->dropped());
}

// Median over pixels well exposed in both of log2(radiance a / radiance b).
double MedianLogRatio(const ColorImage& a, double ms_a, const ColorImage& b, double ms_b,
                      const radiometry::InverseResponse& inv) {
  RadianceImage ra, rb;
  radiometry::ConvertToRadiance(a, inv, float(ms_a), ra);
  radiometry::ConvertToRadiance(b, inv, float(ms_b), rb);
  std::vector<double> r;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const std::uint8_t la[3] = {a[k].r, a[k].g, a[k].b}, lb[3] = {b[k].r, b[k].g, b[k].b};
    const float va[3] = {ra[k].x, ra[k].y, ra[k].z}, vb[3] = {rb[k].x, rb[k].y, rb[k].z};
    for (int c = 0; c < 3; ++c)
      if (la[c] > 10 && la[c] < 245 && lb[c] > 10 && lb[c] < 245) r.push_back(std::log2(double(va[c]) / vb[c]));
  }
  if (r.size() < 1000) return 99;
  std::nth_element(r.begin(), r.begin() + long(r.size() / 2), r.end());
  return r[r.size() / 2];
}

TEST(Sensors, ManualExposureFourTimesLongerAgreesInRadiance) {
  SaveTestProfile();
  LiveFrameSource src(ParseLiveSpec("openni:mode=qvga,ae=off,awb=off,exposure=4"));
  EXPECT_TRUE(src.profile().own);
  pipeline::FrameInput f;
  ASSERT_TRUE(src.Next(f));
  while (!f.exposure_ms) ASSERT_TRUE(src.Next(f));
  EXPECT_NEAR(*f.exposure_ms, 4.0, 1e-9);
  const ColorImage short_frame = f.color.Clone();
  const int view = ViewOf(src.last().index);
  LiveOptions longer;
  longer.exposure_ms = 16.0;
  src.ApplyExposure(longer);
  EXPECT_EQ(src.camera().exposure().exposure_raw, 160);
  // The same view again (the path repeats), under the longer exposure.
  for (int n = 0; n < 200; ++n) {
    ASSERT_TRUE(src.Next(f));
    if (f.exposure_ms && ViewOf(src.last().index) == view) break;
  }
  ASSERT_TRUE(f.exposure_ms);
  ASSERT_EQ(ViewOf(src.last().index), view);
  EXPECT_NEAR(*f.exposure_ms, 16.0, 1e-9);
  const double stops = MedianLogRatio(short_frame, 4.0, f.color, 16.0, *src.sensor().response);
  std::printf("[ figures  ] radiance at 4 ms vs 16 ms, same view: median difference %.4f stops\n", stops);
  EXPECT_LT(std::abs(stops), 0.1);
}

TEST(Sensors, AutoExposureAndWhiteBalanceSwitchAsAsked) {
  SaveTestProfile();
  auto cam = OpenNiCamera::Open("", ParseCaptureMode("qvga"));
  ASSERT_TRUE(cam->has_camera_settings());
  EXPECT_TRUE(cam->exposure().auto_exposure);  // the device's default
  cam->SetAutoExposure(false);
  cam->SetAutoWhiteBalance(false);
  EXPECT_FALSE(cam->exposure().auto_exposure);
  EXPECT_FALSE(cam->exposure().auto_white_balance);
  cam->SetExposure(250);
  cam->SetGain(200);
  cam->Flush();
  auto f = cam->Read(2000ms);
  ASSERT_TRUE(f);
  ASSERT_TRUE(f->exposure_raw);
  EXPECT_EQ(*f->exposure_raw, 250);
  EXPECT_EQ(*f->gain, 200);
  cam->SetAutoExposure(true);
  cam->Flush();
  EXPECT_TRUE(cam->exposure().auto_exposure);
  // Frames under auto exposure carry no exposure: the engine estimates it.
  for (int n = 0; n < 5; ++n) {
    auto g = cam->Read(2000ms);
    ASSERT_TRUE(g);
    EXPECT_FALSE(g->exposure_raw);
  }
  cam->SetAutoWhiteBalance(true);
  EXPECT_TRUE(cam->exposure().auto_white_balance);
}

TEST(Sensors, UnplugIsReportedAndReplugReconnects) {
  std::mutex m;
  std::vector<std::pair<std::string, bool>> events;
  HotplugMonitor monitor([&](const std::string& uri, bool connected) {
    std::lock_guard lock(m);
    events.push_back({uri, connected});
  });
  auto cam = OpenNiCamera::Open("", ParseCaptureMode("qvga"));
  ASSERT_TRUE(cam->Read(2000ms));
  g_env.Plug(false);
  bool lost = false;
  for (int n = 0; n < 100 && !lost; ++n) {
    try {
      cam->Read(100ms);
    } catch (const DeviceLost&) {
      lost = true;
    }
  }
  EXPECT_TRUE(lost);
  EXPECT_TRUE(ListDevices().empty());
  g_env.Plug(true);
  for (int n = 0; n < 100 && ListDevices().empty(); ++n) std::this_thread::sleep_for(20ms);
  cam.reset();
  auto again = OpenNiCamera::Open("", ParseCaptureMode("qvga"));
  EXPECT_TRUE(again->Read(2000ms));
  std::lock_guard lock(m);
  ASSERT_GE(events.size(), 2u);
  EXPECT_EQ(events[events.size() - 2], (std::pair<std::string, bool>{"hdrf-test://0", false}));
  EXPECT_EQ(events.back(), (std::pair<std::string, bool>{"hdrf-test://0", true}));
}

std::vector<Pose> Scan(pipeline::FrameSource& src, int frames, sensors::SequenceRecorder* rec,
                       LiveFrameSource* live) {
  pipeline::PipelineOptions o;
  pipeline::ScanSession session(o, src.sensor().camera, src.sensor());
  pipeline::FrameInput f;
  for (int i = 0; i < frames && src.Next(f); ++i) {
    if (rec) rec->Push(live->last().Clone(), live->ExposureMs(live->last()));
    session.Process(f);
  }
  return session.poses();
}

TEST(Sensors, RecordingScannedLaterMatchesTheLiveScan) {
  SaveTestProfile();
  const fs::path folder = g_env.root() / "recording";
  std::vector<Pose> live_poses;
  long written = 0;
  {
    LiveFrameSource live(ParseLiveSpec("openni:mode=qvga,frames=60"));
    SequenceRecorder rec(folder, live.sensor());
    live_poses = Scan(live, 60, &rec, &live);
    const RecordingStats s = rec.Finish();
    EXPECT_TRUE(s.error.empty()) << s.error;
    written = s.written;
  }
  ASSERT_EQ(written, long(live_poses.size()));
  io::SequenceFrameSource played(folder);
  ASSERT_EQ(played.size(), written);
  const std::vector<Pose> replay = Scan(played, played.size(), nullptr, nullptr);
  ASSERT_EQ(replay.size(), live_poses.size());
  double worst = 0;
  for (std::size_t i = 0; i < replay.size(); ++i)
    worst = std::max(worst, (replay[i].translation() - live_poses[i].translation()).norm());
  std::printf("[ figures  ] %zu frames: live vs recorded trajectory, largest difference %.6f mm\n", replay.size(),
              1000 * worst);
  EXPECT_LT(worst, 1e-3);
  // The camera moved (the comparison is not of two standing cameras). Its farthest pose from
  // the first, not its last: the test device's camera goes back and forth along its path in
  // real time, and a scan slowed by other work takes frames that far apart (under a loaded
  // suite the first and last frame of one run were 0.77 cm apart, its frames 50 s apart).
  double farthest = 0;
  for (const Pose& T : live_poses) farthest = std::max(farthest, (T.translation() - live_poses.front().translation()).norm());
  EXPECT_GT(farthest, 0.01);
}

std::uint64_t Hash(const ColorImage& c) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t k = 0; k < c.size(); ++k)
    for (std::uint8_t v : {c[k].r, c[k].g, c[k].b}) h = (h ^ v) * 1099511628211ull;
  return h;
}

TEST(Sensors, OniRoundTripKeepsEveryFrameAndTheExposureSidecar) {
  SaveTestProfile();
  const fs::path file = g_env.root() / "take.oni";
  std::set<std::uint64_t> seen;
  int noted = 0;
  {
    LiveFrameSource live(ParseLiveSpec("openni:mode=qvga,ae=off,exposure=8"));
    OniRecording rec(file, live.camera(), live.sensor());
    pipeline::FrameInput f;
    for (int i = 0; i < 45; ++i) {
      ASSERT_TRUE(live.Next(f));
      rec.NoteFrame(live.last(), live.ExposureMs(live.last()), 1.0);
      seen.insert(Hash(f.color));
      noted += live.ExposureMs(live.last()).has_value();
    }
    rec.Stop();
  }
  EXPECT_EQ(noted, 45);
  OniPlaybackSource play(file);
  EXPECT_GE(play.size(), 45);
  pipeline::FrameInput f;
  int frames = 0, with_exposure = 0, matched = 0;
  while (play.Next(f)) {
    ++frames;
    if (f.exposure_ms) {
      ++with_exposure;
      EXPECT_NEAR(*f.exposure_ms, 8.0, 1e-9);
    }
    matched += seen.count(Hash(f.color)) > 0;
    EXPECT_EQ(f.depth_m.width(), 320);
  }
  std::printf("[ figures  ] .oni: %d frames recorded, %d played back, %d of the 45 read live found, %d with "
              "exposure\n",
              play.size(), frames, matched, with_exposure);
  EXPECT_EQ(frames, play.size());
  EXPECT_EQ(matched, 45);
  EXPECT_GE(with_exposure, 45);
}

TEST(Sensors, FullDiskLeavesAReadableSequence) {
  const fs::path mnt = g_env.root() / "small";
  fs::create_directories(mnt);
  if (mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=4m") != 0)
    GTEST_SKIP() << "SKIPPED: cannot mount a small tmpfs here (needs root and mount rights): " << std::strerror(errno);
  struct Unmount {
    fs::path p;
    ~Unmount() { umount2(p.c_str(), MNT_DETACH); }
  } unmount{mnt};
  sim::SimOptions so;
  so.width = 640;
  so.height = 480;
  so.frames = 40;
  so.depth_scale = 1000;
  sim::SyntheticSource src(so);
  SensorInfo sensor = src.sensor();
  sensor.synthetic.reset();
  const fs::path folder = mnt / "take";
  RecordingStats s;
  {
    SequenceRecorder rec(folder, sensor, 4);
    for (int i = 0; i < 40 && !rec.failed(); ++i) {
      sim::SimFrame sf = src.Next();
      LiveFrame lf{std::move(sf.color), std::move(sf.depth), sf.timestamp, i, std::nullopt, std::nullopt};
      while (!rec.Push(lf.Clone(), sf.exposure_ms) && !rec.failed()) std::this_thread::sleep_for(5ms);
    }
    s = rec.Finish();
  }
  std::printf("[ figures  ] 4 MB tmpfs: %ld frames written, then: %s\n", s.written, s.error.c_str());
  EXPECT_NE(s.error.find("the disk is full"), std::string::npos) << s.error;
  EXPECT_GT(s.written, 0);
  EXPECT_LT(s.written, 40);
  const io::SequenceReader seq(folder);
  ASSERT_EQ(long(seq.size()), s.written);
  for (std::size_t i = 0; i < seq.size(); ++i) EXPECT_NO_THROW(seq.ReadFrame(i)) << "frame " << i;
  EXPECT_TRUE(seq.has_exposure());
}

TEST(Sensors, ProfilesFollowTheSerial) {
  const DeviceEntry dev{"Some camera", "Vendor", "usb://1", "SER/42"};
  EXPECT_EQ(ProfilePath("SER/42"), g_env.root() / "xdg" / "hdrfusion" / "sensors" / "SER_42.json");
  const Profile fallback = ProfileFor(dev, ParseCaptureMode("vga"));
  EXPECT_FALSE(fallback.own);
  ASSERT_FALSE(fallback.sensor.warnings.empty());
  EXPECT_NE(fallback.sensor.warnings[0].find("built-in Asus Xtion profile"), std::string::npos);
  SensorInfo mine = sim::BuiltinXtionProfile();
  mine.camera.fx = 600;
  mine.device = SensorInfo::Device{"", "", 0.25};
  SaveProfile("SER/42", mine);
  const Profile own = ProfileFor(dev, ParseCaptureMode("qvga"));
  EXPECT_TRUE(own.own);
  EXPECT_EQ(own.file, ProfilePath("SER/42"));
  EXPECT_FLOAT_EQ(own.sensor.camera.fx, 300.f);  // scaled to 320x240
  EXPECT_EQ(own.sensor.camera.width, 320);
  EXPECT_DOUBLE_EQ(*own.sensor.device->exposure_ms_per_unit, 0.25);
  EXPECT_EQ(own.sensor.device->serial, "SER/42");
}

TEST(Sensors, CliListsRecordsAndScansALiveDevice) {
  SaveTestProfile();
  const fs::path out = g_env.root() / "cli_take";
  auto run = [](const std::string& args) {
    const std::string cmd = std::string(HDRF_CLI) + " " + args + " 2>&1";
    std::string text;
    FILE* p = popen(cmd.c_str(), "r");
    char buf[512];
    while (std::fgets(buf, sizeof buf, p)) text += buf;
    const int st = pclose(p);
    return std::pair{WIFEXITED(st) ? WEXITSTATUS(st) : -1, text};
  };
  auto [st1, list] = run("sensors");
  EXPECT_EQ(st1, 0) << list;
  EXPECT_NE(list.find(kSerial), std::string::npos) << list;
  EXPECT_NE(list.find(ProfilePath(kSerial).string()), std::string::npos) << list;
  auto [st2, rec] = run("record --out " + out.string() + " --frames 20 --mode qvga --exposure 6");
  EXPECT_EQ(st2, 0) << rec;
  EXPECT_NE(rec.find("recorded 20 frames"), std::string::npos) << rec;
  const io::SequenceReader seq(out);
  EXPECT_EQ(seq.size(), 20u);
  int with = 0;
  for (const auto& fi : seq.frames()) with += fi.exposure_ms && std::abs(*fi.exposure_ms - 6.0) < 1e-9;
  EXPECT_EQ(with, 20);
  auto [st3, scan] = run("scan openni:mode=qvga,frames=15 --out " + (g_env.root() / "cli_scan").string());
  EXPECT_EQ(st3, 0) << scan;
  EXPECT_TRUE(fs::exists(g_env.root() / "cli_scan" / "mesh.ply"));
}

}  // namespace
