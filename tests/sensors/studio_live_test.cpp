// The studio with a live camera: the test OpenNI2 driver (tests/sensors/CMakeLists.txt) as
// the device, the window on a real X server (Xvfb, as the other studio tests). The sensor
// list follows plug events; the preview runs before a scan; the exposure controls reach the
// camera; a recording from the studio is a readable sequence; an unplug during a scan pauses
// it and keeps the model, and the replug resumes the same scan.
#include <gtest/gtest.h>
#include <unistd.h>

#include <QApplication>
#include <algorithm>
#include <QCheckBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QPushButton>
#include <QRegularExpression>
#include <QSettings>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QElapsedTimer>
#include <QTest>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/se3.h"
#include "gui/image_view.h"
#include "gui/main_window.h"
#include "gui/sensor_panel.h"
#include "gui/vtk_view.h"
#include "io/sequence.h"
#include "io/source_spec.h"
#include "sensors/profiles.h"
#include "sim/builtin_sensor.h"
#include "support/qt_wait.h"
#include "support/test_support.h"

namespace hdrf::gui {
namespace {

namespace fs = std::filesystem;

const char* kSerial = "HDRF-SIM-0001";
fs::path g_root;

bool HaveDisplay() { return !qEnvironmentVariableIsEmpty("DISPLAY"); }

void Plug(bool on) { std::ofstream(g_root / "control") << (on ? "plugged\n" : "unplugged\n"); }

void FreshSettings() {
  QSettings s;
  s.clear();
  s.sync();
}

// The test device's own profile: the built-in response, exposure unit 0.1 ms.
void SaveTestProfile() {
  SensorInfo s = sim::BuiltinXtionProfile();
  s.device = SensorInfo::Device{kSerial, "test device", 0.1};
  sensors::SaveProfile(kSerial, s);
}

template <typename T>
T* Child(MainWindow& w, const char* name) {
  T* c = w.findChild<T*>(name);
  EXPECT_NE(c, nullptr) << name;
  return c;
}

// Frames scanned so far (a preview snapshot carries the model's count as its index).
int Scanned(const MainWindow& w) { return w.latest() ? w.latest()->report.index + 1 : 0; }

void SaveDocsShot(MainWindow& w, const char* name) {
  const QString dir = qEnvironmentVariable("HDRF_DOCS_SHOTS");
  if (dir.isEmpty()) return;
  QTest::qWait(300);
  w.SaveScreenshot(dir + "/" + name);
}

TEST(StudioLive, ListsOnPlugEventsPreviewsControlsAndRecords) {
  if (!HaveDisplay()) GTEST_SKIP() << "no X display and no xvfb-run: cannot host OpenGL widgets";
  FreshSettings();
  SaveTestProfile();
  StudioOptions o;
  o.source = "synthetic:frames=5,size=160x120";
  MainWindow w(o);
  w.resize(1600, 1000);
  w.show();
  SensorPanel* panel = w.sensor_panel();
  ASSERT_NE(panel, nullptr);
  // The list: the device with its serial; it follows unplug and replug.
  ASSERT_TRUE(test::WaitUntil([&] { return panel->device_count() == 1 && panel->device_text(0).contains(kSerial); }, 20000)) << "panel->device_count() == 1 && panel->device_text(0).contains(kSerial)";
  Plug(false);
  ASSERT_TRUE(test::WaitUntil([&] { return panel->device_text(0).contains("No camera"); }, 20000)) << "panel->device_text(0).contains('No camera')";
  Plug(true);
  ASSERT_TRUE(test::WaitUntil([&] { return panel->device_text(0).contains(kSerial); }, 20000)) << "panel->device_text(0).contains(kSerial)";

  // Preview: the camera's frames show before any scan; no frame goes into a model.
  w.dock("sensor")->raise();
  Child<QPushButton>(w, "sensor_open")->click();
  ASSERT_TRUE(test::WaitUntil([&] { return w.latest() && w.latest()->preview && w.latest()->live; }, 30000)) << "w.latest() && w.latest()->preview && w.latest()->live";
  EXPECT_TRUE(w.source_text().startsWith(QString("openni:device=") + kSerial)) << w.source_text().toStdString();
  ASSERT_TRUE(test::WaitUntil([&] { return w.view("colour")->DistinctLevels() > 8 && w.view("depth")->DistinctLevels() > 8; }, 20000)) << "w.view('colour')->DistinctLevels() > 8 && w.view('depth')->DistinctLevels() > 8";
  ASSERT_TRUE(test::WaitUntil([&] { return panel->status_text().contains("frames/s"); }, 20000)) << "panel->status_text().contains('frames/s')";
  QTest::qWait(1000);
  EXPECT_EQ(Scanned(w), 0) << "the preview must not scan";
  EXPECT_GT(w.latest()->live->fps, 20.0);

  // Exposure controls: auto exposure off, 8 ms, gain 200; then auto exposure back on.
  Child<QCheckBox>(w, "sensor_ae")->setChecked(false);
  ASSERT_TRUE(test::WaitUntil([&] { return w.latest() && w.latest()->live && !w.latest()->live->exposure.auto_exposure; }, 20000)) << "w.latest() && w.latest()->live && !w.latest()->live->exposure.auto_exposure";
  Child<QDoubleSpinBox>(w, "sensor_exposure")->setValue(8.0);
  ASSERT_TRUE(test::WaitUntil([&] { return w.latest()->live->exposure.exposure_raw == 80; }, 20000)) << "w.latest()->live->exposure.exposure_raw == 80";
  ASSERT_TRUE(test::WaitUntil([&] { return panel->status_text().contains("exposure 8.0 ms"); }, 20000)) << "panel->status_text().contains('exposure 8.0 ms')";
  Child<QSpinBox>(w, "sensor_gain")->setValue(200);
  ASSERT_TRUE(test::WaitUntil([&] { return w.latest()->live->exposure.gain == 200; }, 20000)) << "w.latest()->live->exposure.gain == 200";
  Child<QCheckBox>(w, "sensor_awb")->setChecked(false);
  ASSERT_TRUE(test::WaitUntil([&] { return !w.latest()->live->exposure.auto_white_balance; }, 20000)) << "!w.latest()->live->exposure.auto_white_balance";
  SaveDocsShot(w, "studio-live.png");

  // Record about 40 frames from the preview; the panel counts them; the folder is a sequence.
  QTemporaryDir dir;
  const QString folder = dir.filePath("recording");
  panel->SetRecordingPath(folder);
  Child<QPushButton>(w, "sensor_record")->click();
  ASSERT_TRUE(test::WaitUntil([&] { return panel->recording_text().contains("Recording to"); }, 20000)) << "panel->recording_text().contains('Recording to')";
  ASSERT_TRUE(test::WaitUntil([&] { return w.latest()->live->recording_stats.written >= 40; }, 30000)) << "w.latest()->live->recording_stats.written >= 40";
  SaveDocsShot(w, "studio-recording.png");
  Child<QPushButton>(w, "sensor_record")->click();
  ASSERT_TRUE(test::WaitUntil([&] { return panel->recording_text().startsWith("Recorded"); }, 30000)) << "panel->recording_text().startsWith('Recorded')";
  const QRegularExpressionMatch m =
      QRegularExpression("Recorded (\\d+) frames \\(([0-9.]+) MB, ([0-9.]+) s, (\\d+) dropped\\)").match(panel->recording_text());
  ASSERT_TRUE(m.hasMatch()) << panel->recording_text().toStdString();
  const int written = m.captured(1).toInt();
  std::printf("studio recording: %s; preview %.1f frames/s\n", qPrintable(panel->recording_text()), w.latest()->live->fps);
  EXPECT_GE(written, 40);
  EXPECT_EQ(m.captured(4).toInt(), 0);
  EXPECT_GT(m.captured(2).toDouble(), 0.1);
  EXPECT_GT(m.captured(3).toDouble(), 1.0);
  EXPECT_EQ(Scanned(w), 0);
  auto seq = io::OpenSource(folder.toStdString(), "srgb");
  EXPECT_EQ(seq->size(), written);
  pipeline::FrameInput f;
  ASSERT_TRUE(seq->Next(f));
  EXPECT_EQ(f.color.width(), 640);
  // Auto exposure was off: each frame's exposure and gain kept, and a scan of the recording
  // is told their product (8 ms at gain 200, twice the unit gain: 16).
  ASSERT_TRUE(f.exposure_ms.has_value());
  EXPECT_NEAR(*f.exposure_ms, 16.0, 1e-6);
  const io::SequenceReader reader(folder.toStdString());
  ASSERT_TRUE(reader.frames()[0].exposure_ms.has_value());
  EXPECT_NEAR(*reader.frames()[0].exposure_ms, 8.0, 1e-6);
  ASSERT_TRUE(reader.frames()[0].gain.has_value());
  EXPECT_NEAR(*reader.frames()[0].gain, 2.0, 1e-9);
}

TEST(StudioLive, UnplugDuringAScanPausesAndKeepsTheModelReplugResumes) {
  if (!HaveDisplay()) GTEST_SKIP() << "no X display and no xvfb-run: cannot host OpenGL widgets";
  FreshSettings();
  SaveTestProfile();
  Plug(true);
  StudioOptions o;
  o.source = QString("openni:device=") + kSerial + ",mode=qvga";
  o.device = "cpu";
  o.autostart = true;
  MainWindow w(o);
  w.resize(1600, 1000);
  w.show();
  ASSERT_TRUE(test::WaitUntil([&] { return Scanned(w) >= 20 && !w.latest()->preview; }, 120000)) << "Scanned(w) >= 20 && !w.latest()->preview";
  ASSERT_TRUE(test::WaitUntil([&] { return w.view3d()->mesh_triangles() > 1000; }, 60000)) << "w.view3d()->mesh_triangles() > 1000";
  Plug(false);
  ASSERT_TRUE(test::WaitUntil([&] { return w.error_text().contains("unplugged"); }, 20000)) << "w.error_text().contains('unplugged')";
  EXPECT_TRUE(w.error_text().contains("model is kept")) << w.error_text().toStdString();
  const int at_unplug = Scanned(w);
  // The surface of the model as it was at the unplug (meshed off the scan's thread) is shown.
  ASSERT_TRUE(test::WaitUntil([&] { return w.surface_final(); }, 20000)) << "w.surface_final()";
  const auto triangles = w.view3d()->mesh_triangles();
  QTest::qWait(1500);
  EXPECT_EQ(Scanned(w), at_unplug) << "no frame may be scanned while the camera is away";
  EXPECT_EQ(w.view3d()->mesh_triangles(), triangles) << "the model must be kept";
  EXPECT_TRUE(w.start_enabled());
  SaveDocsShot(w, "studio-unplugged.png");
  // The camera comes back: the same scan goes on (frames counted on from where it stopped).
  Plug(true);
  ASSERT_TRUE(test::WaitUntil([&] { return Scanned(w) >= at_unplug + 20 && !w.latest()->preview; }, 120000)) << "Scanned(w) >= at_unplug + 20 && !w.latest()->preview";
  EXPECT_TRUE(w.error_text().isEmpty()) << w.error_text().toStdString();
  const auto& s = *w.latest();
  EXPECT_EQ(int(s.trajectory.size()), Scanned(w));
  // Across the gap the pose moves as little as between any two frames (the device held still).
  double largest = 0;
  for (std::size_t i = 1; i < s.trajectory.size(); ++i)
    largest = std::max(largest, (s.trajectory[i - 1].inverse() * s.trajectory[i]).translation().norm());
  const double gap = (s.trajectory[at_unplug - 1].inverse() * s.trajectory[at_unplug]).translation().norm();
  std::printf("studio unplug at %d frames, resumed to %d; step across the gap %.1f mm, largest step %.1f mm\n",
              at_unplug, Scanned(w), 1000 * gap, 1000 * largest);
  EXPECT_LT(gap, 0.05);
  EXPECT_LT(largest, 0.05);
  // The model grew on: the device held still while it was away, so tracking continues.
  EXPECT_FALSE(s.report.tracking.lost) << s.report.tracking.why;
  // Paused, the whole surface follows the scan's preview: the kept model and what the
  // frames since the replug added (at least the surface shown at the unplug).
  w.PauseScan();
  ASSERT_TRUE(test::WaitUntil([&] { return w.surface_final() && w.view3d()->mesh_triangles() >= triangles * 9 / 10; }, 60000))
      << w.view3d()->mesh_triangles() << " triangles after the replug, " << triangles << " at the unplug";
}

}  // namespace
}  // namespace hdrf::gui

int main(int argc, char** argv) {
  const bool display = hdrf::test::EnsureDisplay(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (!display) return RUN_ALL_TESTS();
  // Before OpenNI2 loads the driver (it reads these once): the hot-plug control file, private
  // profile and settings folders.
  QTemporaryDir root;
  hdrf::gui::g_root = root.path().toStdString();
  hdrf::gui::Plug(true);
  setenv("HDRF_TEST_DEVICE_CONTROL", (hdrf::gui::g_root / "control").c_str(), 1);
  // The camera moves slowly (a view per 8 frames): a CPU scan on two cores takes a few frames
  // a second, and an operator scanning a room moves slowly too.
  setenv("HDRF_TEST_DEVICE_FRAMES_PER_VIEW", "8", 1);
  setenv("XDG_DATA_HOME", (hdrf::gui::g_root / "data").c_str(), 1);
  setenv("XDG_CONFIG_HOME", (hdrf::gui::g_root / "config").c_str(), 1);
  setenv("XDG_STATE_HOME", (hdrf::gui::g_root / "state").c_str(), 1);  // autosaves stay in the test folder
  hdrf::gui::VtkView::SetDefaultSurfaceFormat();
  QApplication app(argc, argv);
  QApplication::setOrganizationName("HDRFusionTest");
  QApplication::setApplicationName("StudioLiveTests");
  return RUN_ALL_TESTS();
}
