// Runs the real `hdrfusion` binary as a user would and checks exit status and output.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/error.h"
#include "io/asset_export.h"
#include <iterator>
#include "common/host_memory.h"
#include "io/exr.h"
#include "io/output_file.h"
#include "io/ply.h"
#include "io/image_io.h"
#include "io/sensor_json.h"
#include "io/sequence.h"
#include "support/test_support.h"

namespace hdrf {
namespace {

namespace fs = std::filesystem;

using RunResult = test::CommandResult;

RunResult RunCli(const std::string& args) { return test::RunCommand(std::string(HDRF_CLI) + " " + args); }

TEST(Cli, InfoReportsASequenceWrittenByAnotherTool) {
  test::TempDir dir;
  const fs::path seq = dir / "seq";
  fs::create_directories(seq / "rgb");
  fs::create_directories(seq / "depth");
  std::string rgb, depth, exposure, gt;
  for (int i = 0; i < 31; ++i) {
    const std::string t = std::to_string(1000.0 + i / 30.0);
    cv::imwrite((seq / "rgb" / (t + ".png")).string(), cv::Mat(12, 16, CV_8UC3, cv::Scalar(50)));
    cv::Mat d(12, 16, CV_16UC1, cv::Scalar(i % 2 ? 0 : 7500));  // every other frame empty
    cv::imwrite((seq / "depth" / (t + ".png")).string(), d);
    rgb += t + " rgb/" + t + ".png\n";
    depth += t + " depth/" + t + ".png\n";
    exposure += t + " " + std::to_string(3 << (i % 4)) + "\n";
    gt += t + " 0 0 " + std::to_string(i * 0.01) + " 0 0 0 1\n";
  }
  test::WriteText(seq / "rgb.txt", rgb);
  test::WriteText(seq / "depth.txt", depth);
  test::WriteText(seq / "exposure.txt", exposure);
  test::WriteText(seq / "groundtruth.txt", gt);
  test::WriteText(seq / "sensor.json",
                  R"({"camera": {"width": 16, "height": 12, "fx": 10, "fy": 10, "cx": 7.5,
                      "cy": 5.5}, "depth": {"scale": 5000},
                      "synthetic": {"generator": "another simulator", "version": 2}})");
  // The other tool's "synthetic" block is not ours: a warning, never a refusal.
  const RunResult r = RunCli("info " + seq.string() + " --depth-samples 31");
  EXPECT_NE(r.output.find("warning:"), std::string::npos) << r.output;
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("frames        31"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1.000 s (30.00 Hz)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("16x12"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("3 .. 24 ms"), std::string::npos) << r.output;
  // 16 of 31 frames have full depth.
  EXPECT_NE(r.output.find("51.6 % valid pixels, 1.500 .. 1.500 m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ground truth  yes (31 of 31 frames)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("response      none"), std::string::npos) << r.output;
}

TEST(Cli, InfoOnBadInputFailsWithOneLineNamingTheFile) {
  test::TempDir dir;
  RunResult r = RunCli("info " + (dir / "missing").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("missing"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  test::WriteText(dir / "s" / "sensor.json", "{\"camera\": {}}");
  r = RunCli("info " + (dir / "s").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("sensor.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("camera.width"), std::string::npos) << r.output;
}

TEST(Cli, RadianceRefusesMissingCalibrationAndHonoursSrgbFallback) {
  test::TempDir dir;
  cv::imwrite((dir / "c.png").string(), cv::Mat(4, 4, CV_8UC3, cv::Scalar(0, 0, 255)));
  RunResult r = RunCli("radiance " + (dir / "c.png").string() + " --out " + (dir / "r.exr").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--response srgb"), std::string::npos) << r.output;
  r = RunCli("radiance " + (dir / "c.png").string() + " --response srgb --exposure 2 --out " +
          (dir / "r.exr").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const RadianceImage img = io::ReadExr(dir / "r.exr");
  EXPECT_FLOAT_EQ(img(2, 2).x, 0.5f);  // red 255 -> 1.0 linear, / 2 ms
  EXPECT_FLOAT_EQ(img(2, 2).z, 0.0f);
}

// An output is checked before any work: one that is the command's input, data under
// another format's name, a link, a folder that is a file, a plots folder that is a file.
// Each is refused naming the path, and the input is left byte for byte as it was.
TEST(Cli, OutputsThatAreInputsOrMisnamedAreRefusedBeforeAnyWork) {
  test::TempDir dir;
  const std::string png = (dir / "c.png").string();
  cv::imwrite(png, cv::Mat(4, 4, CV_8UC3, cv::Scalar(0, 80, 255)));
  const auto bytes = [](const std::string& f) {
    std::ifstream in(f, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const std::string before = bytes(png);
  RunResult r = RunCli("radiance " + png + " --response srgb --exposure 2 --out " + png);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("must end in .exr"), std::string::npos) << r.output;
  EXPECT_EQ(bytes(png), before) << "the input image was replaced";
  r = RunCli("radiance " + png + " --response srgb --exposure 2 --out " + (dir / "r.png").string());
  EXPECT_NE(r.status, 0);
  EXPECT_FALSE(fs::exists(dir / "r.png")) << "OpenEXR data was written under a .png name";
  const std::string exr = (dir / "r.exr").string();
  ASSERT_EQ(RunCli("radiance " + png + " --response srgb --exposure 2 --out " + exr).status, 0);
  const std::string exr_before = bytes(exr);
  r = RunCli("tonemap " + exr + " --out " + exr);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("is an input of this command"), std::string::npos) << r.output;
  EXPECT_EQ(bytes(exr), exr_before) << "the tone-mapped image replaced its input";
  fs::create_symlink(dir / "elsewhere.png", dir / "link.png");
  r = RunCli("tonemap " + exr + " --out " + (dir / "link.png").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("symbolic link"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "elsewhere.png")) << "written through a link";
  r = RunCli("scan synthetic:frames=3,size=64x48 --out " + png + "/scan");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("is a file, not a folder"), std::string::npos) << r.output;
  // calibrate: a --plots that is a file is refused before the fit, and no sensor.json written.
  const std::string sweep = (dir / "sweep").string();
  ASSERT_EQ(RunCli("simulate --out " + sweep + " --sweep --sweep-repeats 2 --size 64x48").status, 0);
  r = RunCli("calibrate " + sweep + " --out " + (dir / "s.json").string() + " --plots " + png);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("is not a folder"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("response ("), std::string::npos) << "the fit ran before the output was checked";
  EXPECT_FALSE(fs::exists(dir / "s.json"));
  r = RunCli("calibrate " + sweep + " --out " + (dir / "s.txt").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("must end in .json"), std::string::npos) << r.output;
}

// Two scans into one folder: the second is refused at once, naming the folder, while the
// first holds it; once it is released a scan goes ahead, and leaves no lock file behind.
TEST(Cli, ASecondScanIntoTheSameFolderIsRefused) {
  test::TempDir dir;
  const fs::path out = dir / "scan";
  fs::create_directories(out);
  {
    const io::FolderLock held(out);  // as a running scan holds it
    const RunResult r = RunCli("scan synthetic:frames=3,size=64x48 --out " + out.string());
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("is writing into this folder"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("process " + std::to_string(::getpid())), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out / "trajectory.txt"));
  }
  const RunResult r = RunCli("scan synthetic:frames=3,size=64x48 --out " + out.string() + " --autosave 0");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "trajectory.txt"));
  EXPECT_FALSE(fs::exists(out / ".hdrfusion-lock"));
}

// eval of a trajectory that does not belong to the sequence (no timestamp in common) names
// both files and says what is missing, instead of "got 0 poses".
TEST(Cli, EvalOfAnotherSequencesTrajectoryNamesBothFiles) {
  test::TempDir dir;
  const std::string seq = (dir / "seq").string();
  ASSERT_EQ(RunCli("simulate --out " + seq + " --frames 5 --size 64x48").status, 0);
  fs::create_directories(dir / "scan");
  test::WriteText(dir / "scan" / "trajectory.txt",
                  "1000.0 0 0 0 0 0 0 1\n1000.1 0 0 0 0 0 0 1\n1000.2 0 0 0 0 0 0 1\n1000.3 0 0 0 0 0 0 1\n");
  const RunResult r = RunCli("eval " + seq + " " + (dir / "scan").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("trajectory.txt: 4 poses, of which 0 have a ground-truth pose"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("groundtruth.txt (5 poses there)"), std::string::npos) << r.output;
}

// calibrate SWEEP --out SWEEP/sensor.json completes the sweep's own file: the response and
// noise are written, and what other tools put there is kept.
TEST(Cli, CalibrationOverASensorJsonKeepsOtherToolsKeys) {
  test::TempDir dir;
  const std::string sweep = (dir / "sweep").string();
  ASSERT_EQ(RunCli("simulate --out " + sweep + " --sweep --sweep-repeats 3 --size 96x72").status, 0);
  auto j = nlohmann::json::parse(test::ReadText(dir / "sweep" / "sensor.json"));
  j["vendor_tool"] = {{"lens", "2.8 mm"}, {"checked", true}};
  j["hdrfusion"]["note"] = "kept";
  test::WriteText(dir / "sweep" / "sensor.json", j.dump(2));
  const RunResult r = RunCli("calibrate " + sweep + " --out " + sweep + "/sensor.json");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto after = nlohmann::json::parse(test::ReadText(dir / "sweep" / "sensor.json"));
  EXPECT_EQ(after["vendor_tool"]["lens"], "2.8 mm");
  EXPECT_EQ(after["hdrfusion"]["note"], "kept");
  EXPECT_TRUE(after.contains("response"));
  EXPECT_TRUE(after.contains("noise"));
  EXPECT_TRUE(io::ReadSensorJson(dir / "sweep" / "sensor.json").response.has_value());
}

TEST(Cli, UnknownSubcommandAndMissingArgumentsFail) {
  EXPECT_NE(RunCli("frobnicate").status, 0);
  EXPECT_NE(RunCli("info").status, 0);
  EXPECT_EQ(RunCli("--version").status, 0);
  // The paper's experiments are not part of the product's tool (hdrfusion-experiments).
  for (const char* gone : {"bench --suite tracking", "bench --suite paper", "contact-sheet x --out y.png"}) {
    const RunResult r = RunCli(gone);
    EXPECT_NE(r.status, 0) << gone;
  }
  EXPECT_EQ(RunCli("bench --suite sim --frames 5").status, 0);
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

TEST(Cli, SimulateWritesASequenceThatInfoAndTheReaderAccept) {
  test::TempDir dir;
  const std::string out = (dir / "sim").string();
  RunResult r = RunCli("simulate --out " + out + " --frames 12 --size 64x48 --ae flicker --seed 3");
  ASSERT_EQ(r.status, 0) << r.output;
  const io::SequenceReader seq(out);
  ASSERT_EQ(seq.size(), 12u);
  EXPECT_TRUE(seq.has_exposure() && seq.has_groundtruth() && seq.has_hdr());
  ASSERT_TRUE(seq.sensor().response && seq.sensor().noise);
  EXPECT_EQ(seq.sensor().camera.width, 64);
  EXPECT_NEAR(seq.sensor().noise->sigma_s[1], 0.032663, 1e-6);  // the built-in Xtion profile
  const io::Frame f = seq.ReadFrame(5);
  EXPECT_EQ(f.color.width(), 64);
  EXPECT_GT(seq.ReadHdr(5)[100].y, 0.f);
  r = RunCli("info " + out);
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("hdr radiance  yes"), std::string::npos) << r.output;
  r = test::RunCommand(std::string(HDRF_EXPERIMENTS) + " contact-sheet " + out + " --out " +
                       (dir / "sheet.png").string() + " --rows 3");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(cv::imread((dir / "sheet.png").string()).cols, 3 * 64 + 8);
}

// A scan whose --out is the sequence it reads rewrote the sequence's sensor.json with the
// curve it had assumed (--response srgb), so that later scans used the guess as calibrated.
TEST(Cli, AScanNeverWritesIntoTheRecordingItReads) {
  test::TempDir dir;
  const std::string seq = (dir / "seq").string();
  ASSERT_EQ(RunCli("simulate --out " + seq + " --frames 6 --size 64x48 --seed 3").status, 0);
  const std::string sensor = test::ReadText(dir / "seq" / "sensor.json");
  for (const std::string out : {seq, seq + "/", (dir / "seq" / ".").string()}) {
    const RunResult r = RunCli("scan " + seq + " --out " + out + " --response srgb");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("is the recording the scan reads"), std::string::npos) << r.output;
  }
  RunResult r = RunCli("scan " + seq + " --out " + (dir / "scan").string() + " --save " + seq + "/x.hdrproj");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("is in the recording the scan reads"), std::string::npos) << r.output;
  // A project is a .hdrproj file (sensor.json, p.txt were taken and written as projects).
  r = RunCli("scan " + seq + " --out " + (dir / "scan").string() + " --save " + seq + "/sensor.json");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("'--save': a project file's name ends in .hdrproj, got"), std::string::npos) << r.output;
  EXPECT_EQ(test::ReadText(dir / "seq" / "sensor.json"), sensor);
  EXPECT_FALSE(std::filesystem::exists(dir / "seq" / "trajectory.txt"));
}

TEST(Cli, SimulateSweepAndBadSettings) {
  test::TempDir dir;
  RunResult r = RunCli("simulate --out " + (dir / "sweep").string() +
                       " --sweep --sweep-exposures 1,4,16 --sweep-repeats 3 --size 32x24");
  ASSERT_EQ(r.status, 0) << r.output;
  const io::SequenceReader seq((dir / "sweep").string());
  ASSERT_EQ(seq.size(), 9u);
  EXPECT_DOUBLE_EQ(*seq.frames()[3].exposure_ms, 4.0);
  r = RunCli("simulate --out " + (dir / "x").string() + " --size 10by10");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--size"), std::string::npos) << r.output;
  // Numbers with something after them, or a sign an unsigned value cannot take, were read up
  // to where they stopped making sense and taken.
  for (const char* bad : {"--size 320x240junk", "--size 0x240"}) {
    r = RunCli("simulate --out " + (dir / "x").string() + " " + bad);
    EXPECT_EQ(r.status, 1) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--size"), std::string::npos) << r.output;
  }
  for (const char* bad : {"seed=-1", "frames=12abc", "exposure=8ms", "seed="}) {
    r = RunCli("scan synthetic:" + std::string(bad) + " --out " + (dir / "x").string());
    EXPECT_EQ(r.status, 1) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("cannot parse '" + std::string(bad) + "'"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "x"));
  r = RunCli("simulate --out " + (dir / "x").string() + " --ae list --exposures 3,abc");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("'abc'"), std::string::npos) << r.output;
  // "nan" and "inf" read as numbers pass a range check (--autosave nan was taken); a bad
  // --tone was reported as --op.
  for (const auto& [flags, said] : {std::pair{" --autosave nan", "setting '--autosave': 'nan' is not a finite number"},
                                    std::pair{" --volume.voxel_m INF", "setting 'volume.voxel_m': 'INF' is not a number"},
                                    std::pair{" --tone bogus", "setting '--tone': unknown tone-mapping operator 'bogus'"}}) {
    r = RunCli("scan synthetic:frames=3 --out " + (dir / "x").string() + flags);
    EXPECT_EQ(r.status, 1) << flags << ": " << r.output;
    EXPECT_NE(r.output.find(said), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "x"));
  // An existing, non-empty output folder is refused and left alone.
  r = RunCli("simulate --out " + (dir / "sweep").string() + " --frames 2 --size 32x24");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("not empty"), std::string::npos) << r.output;
  EXPECT_EQ(io::SequenceReader((dir / "sweep").string()).size(), 9u);
}

// Values that used to be taken quietly, or to hang the engine, are refused naming the flag or
// the key, before anything is written.
TEST(Cli, QuietlyWrongValuesAndImpossibleIntrinsicsAreRefused) {
  test::TempDir dir;
  for (const char* bad : {"--exposure -5", "--exposure 0", "--ae list --exposures 3,-2", "--frames 0",
                          "--sweep --sweep-repeats 0"}) {
    const RunResult r = RunCli("simulate --out " + (dir / "neg").string() + " --size 32x24 " + bad);
    EXPECT_NE(r.status, 0) << bad;
    const std::string flag = std::string(bad).substr(std::string(bad).rfind("--"));
    EXPECT_NE(r.output.find(flag.substr(0, flag.find(' '))), std::string::npos) << bad << ": " << r.output;
    EXPECT_FALSE(fs::exists(dir / "neg")) << bad;
  }
  const std::string seq = (dir / "seq").string();
  ASSERT_EQ(RunCli("simulate --out " + seq + " --frames 3 --size 64x48").status, 0);
  RunResult r = RunCli("scan " + seq + " --frames 0 --out " + (dir / "o0").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--frames"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "o0"));
  // A principal point at 1e30 pixels, a focal length of 1e-5 pixels: the scan used to run
  // without end in integration; now info and scan both say which key is wrong.
  for (const auto& [key, value] : {std::pair{"cx", 1e30}, {"fx", 1e-5}, {"cy", 3.5e38}}) {
    const fs::path bad = dir / (std::string("bad_") + key);
    fs::copy(seq, bad, fs::copy_options::recursive);
    nlohmann::json j = nlohmann::json::parse(std::ifstream(bad / "sensor.json"));
    j["camera"][key] = value;
    std::ofstream(bad / "sensor.json") << j.dump();
    for (const std::string cmd : {"info " + bad.string(), "scan " + bad.string() + " --out " + (dir / "o").string()}) {
      r = RunCli(cmd);
      EXPECT_EQ(r.status, 1) << cmd << ": " << r.output;
      EXPECT_NE(r.output.find(std::string("'camera.") + key + "'"), std::string::npos) << cmd << ": " << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "o"));
  }
}

// The benchmark asked for the GPU alone either measures it or says why it cannot: never an
// empty table and success.
TEST(Cli, BenchOnTheGpuAloneMeasuresItOrSaysWhyNot) {
  const RunResult r = test::RunCommand(std::string(HDRF_BENCH) + " --device cuda --frames 5 --case 64x48x40");
  if (r.status == 0) {
    EXPECT_NE(r.output.find("| cuda |"), std::string::npos) << r.output;
  } else {
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("no CUDA device can be used here"), std::string::npos) << r.output;
  }
}

// The stage table against the memory-bandwidth floors: every stage of the CPU rows is there,
// with a measured copy bandwidth, and none takes less than the time its least bytes need. Run
// at two frame sizes, the margin table's line through the two passes through both rows'
// figures (fixed + k x floor gives each stage's time at either size).
TEST(Cli, BenchSetsEachStageAgainstItsBandwidthFloor) {
  const RunResult r =
      test::RunCommand(std::string(HDRF_BENCH) + " --device cpu --frames 5 --case 64x48x40 --case 128x96x40");
  ASSERT_EQ(r.status, 0) << r.output;
  std::map<std::string, std::array<double, 2>> stage_ms, stage_floor;  // at 64x48, 128x96
  for (int size = 0; size < 2; ++size) {
    const std::string key = size == 0 ? "| cpu | compact | 64x48 | " : "| cpu | compact | 128x96 | ";
    for (const char* stage : {"convert", "normalize", "track", "integrate", "raycast"}) {
      std::size_t at = r.output.find(key);
      for (; at != std::string::npos; at = r.output.find(key, at + 1)) {
        const std::size_t eol = r.output.find('\n', at);
        const std::string line = r.output.substr(at + key.size(), eol - at - key.size());
        if (line.find(std::string("| ") + stage + " |") == std::string::npos) continue;
        double gbs = 0, ms = 0, mb = 0, floor_ms = 0, times = 0;
        char bus[16], name[32], upload[16];
        ASSERT_EQ(std::sscanf(line.c_str(), "%lf | %15s | %31s | %lf | %lf | %15s | %lf | %lf |", &gbs, bus, name, &ms, &mb,
                              upload, &floor_ms, &times),
                  8)
            << line;
        EXPECT_STREQ(bus, "-") << line;  // no bus on the CPU
        EXPECT_GT(gbs, 0.1) << line;
        EXPECT_GT(mb, 0) << line;
        EXPECT_NEAR(floor_ms, mb / gbs, 1e-4 + floor_ms * (0.5 / gbs + 0.01)) << line;  // (GB/s to the unit)
        EXPECT_GE(ms, floor_ms) << line;
        stage_ms[stage][std::size_t(size)] = ms;
        stage_floor[stage][std::size_t(size)] = floor_ms;
        break;
      }
    }
  }
  ASSERT_EQ(stage_ms.size(), 5u) << r.output;
  const std::size_t margins = r.output.find("x floor at the margin");
  ASSERT_NE(margins, std::string::npos) << r.output;
  int fitted = 0;
  for (const auto& [stage, ms] : stage_ms) {
    const std::string key = "| cpu | compact | 64x48 -> 128x96 | 40 mm | " + stage + " | ";
    const std::size_t at = r.output.find(key, margins);
    if (stage_floor[stage][1] <= stage_floor[stage][0]) continue;  // a floor that did not grow has no line
    ASSERT_NE(at, std::string::npos) << stage << "\n" << r.output.substr(margins);
    double m1 = 0, m2 = 0, f1 = 0, f2 = 0, fixed = 0, k = 0;
    ASSERT_EQ(std::sscanf(r.output.c_str() + at + key.size(), "%lf / %lf | %lf / %lf | %lf | %lf |", &m1, &m2, &f1, &f2, &fixed, &k),
              6)
        << r.output.substr(at, 200);
    EXPECT_DOUBLE_EQ(m1, ms[0]) << stage;
    EXPECT_DOUBLE_EQ(m2, ms[1]) << stage;
    // Printed to 0.001 ms, the floors to 0.0001 and k to a tenth: the line meets both points
    // within that rounding.
    const double tol = 0.002 + 0.05 * f2 + 1e-4 * std::abs(k);
    EXPECT_NEAR(fixed + k * f1, m1, tol) << stage;
    EXPECT_NEAR(fixed + k * f2, m2, tol) << stage;
    ++fitted;
  }
  EXPECT_GE(fitted, 4) << r.output.substr(margins);
  // The tracking stage divided over its Gauss-Newton iterations: the levels' means add up to
  // the frame's, and each iteration takes some of the stage's time.
  const std::size_t it = r.output.find("iterations (level 0 / 1 / 2)");
  ASSERT_NE(it, std::string::npos) << r.output;
  const std::size_t row = r.output.find("| cpu | compact | 64x48 | ", it);  // (its line comes first)
  ASSERT_NE(row, std::string::npos) << r.output;
  double l0 = -1, l1 = -1, l2 = -1, all = -1, per = -1;
  ASSERT_EQ(std::sscanf(r.output.c_str() + row, "| cpu | compact | 64x48 | %lf / %lf / %lf | %lf | %lf |", &l0, &l1, &l2,
                        &all, &per),
            5)
      << r.output.substr(row, 120);
  EXPECT_GT(l0, 0);
  EXPECT_NEAR(l0 + l1 + l2, all, 0.25);  // each printed to a tenth
  EXPECT_GT(per, 0);
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

TEST(Cli, CalibrateAndMergeASimulatedSweep) {
  test::TempDir dir;
  const std::string sweep = (dir / "sweep").string();
  RunResult r = RunCli("simulate --out " + sweep + " --sweep --sweep-repeats 3 --size 96x72");
  ASSERT_EQ(r.status, 0) << r.output;
  r = RunCli("calibrate " + sweep + " --out " + (dir / "s.json").string() + " --plots " +
             (dir / "plots").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("noise level function"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("median |deviation|"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("refined on the level thresholds"), std::string::npos) << r.output;
  // The check of the fit: the middle exposure held back and predicted, a verdict.
  EXPECT_NE(r.output.find("held back"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("verdict: good"), std::string::npos) << r.output;
  const SensorInfo s = io::ReadSensorJson(dir / "s.json");
  ASSERT_TRUE(s.response && s.noise);
  EXPECT_FLOAT_EQ(s.response->table[1][128], 1.f);
  EXPECT_EQ(s.camera.width, 96);  // camera block carried over from the sweep
  for (const char* png : {"response.png", "derivative.png", "pcf.png"})
    EXPECT_TRUE(fs::exists(dir / "plots" / png)) << png;
  r = RunCli("merge " + sweep + " --sensor " + (dir / "s.json").string() + " --out " +
             (dir / "hdr.exr").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(io::ReadExr(dir / "hdr.exr").width(), 96);
  // The classic method on request: another curve, said so.
  r = RunCli("calibrate " + sweep + " --out " + (dir / "c.json").string() + " --threshold-passes 0");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("debevec, classic"), std::string::npos) << r.output;
  const SensorInfo classic = io::ReadSensorJson(dir / "c.json");
  double differ = 0;
  for (int z = 10; z < 250; ++z) differ = std::max(differ, double(std::abs(classic.response->table[1][z] - s.response->table[1][z])));
  EXPECT_GT(differ, 1e-4);
  r = RunCli("calibrate " + sweep + " --out " + (dir / "e.json").string() + " --method emor");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--emor-basis"), std::string::npos) << r.output;
}

// Rewrites a sweep's exposure.txt with the exposures in reverse order (the images stay).
void ReverseExposures(const fs::path& sweep) {
  std::ifstream in(sweep / "exposure.txt");
  std::vector<std::string> head, stamp, exposure;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') {
      head.push_back(line);
      continue;
    }
    const auto sp = line.find(' ');
    stamp.push_back(line.substr(0, sp));
    exposure.push_back(line.substr(sp + 1));
  }
  std::ofstream out(sweep / "exposure.txt");
  for (const auto& h : head) out << h << "\n";
  for (std::size_t i = 0; i < stamp.size(); ++i) out << stamp[i] << " " << exposure[exposure.size() - 1 - i] << "\n";
}

// Rewrites a sweep's exposure.txt with an analog gain column: gain(i) for frame i (none: no
// column on that line).
void AddGains(const fs::path& sweep, const std::function<std::optional<double>(int)>& gain) {
  std::ifstream in(sweep / "exposure.txt");
  std::vector<std::string> lines;
  std::string line;
  int i = 0;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != '#')
      if (const std::optional<double> g = gain(i++)) line += " " + std::to_string(*g);
    lines.push_back(line);
  }
  std::ofstream out(sweep / "exposure.txt");
  for (const auto& l : lines) out << l << "\n";
}

// The bad sweeps a new user makes end in a clear message, before the fit where they can,
// and nothing is written.
// The wizard's steps headless: a sweep captured from the synthetic sensor (exposures planned
// from the scene), calibrated, and stored as the profile of its camera's serial; an
// interrupted capture completed with --resume; what capture-sweep refuses.
TEST(Cli, CaptureSweepCalibrateAndStoreTheProfile) {
  test::TempDir dir;
  const std::string env = "XDG_DATA_HOME=" + (dir / "xdg").string() + " ";
  const std::string sweep = (dir / "sweep").string();
  RunResult r = test::RunCommand(env + HDRF_CLI + std::string(" capture-sweep --source synthetic:response=gamma1.8,"
                                                              "size=128x96 --repeats 4 --out ") + sweep);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("plan: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("captured "), std::string::npos) << r.output;
  r = test::RunCommand(env + HDRF_CLI + " calibrate " + sweep + " --out " + (dir / "s.json").string() +
                       " --save-profile");
  ASSERT_EQ(r.status, 0) << r.output;
  const fs::path profile = dir / "xdg" / "hdrfusion" / "sensors" / "HDRF-SYNTHETIC.json";
  ASSERT_TRUE(fs::exists(profile)) << r.output;
  const SensorInfo s = io::ReadSensorJson(profile);
  ASSERT_TRUE(s.response);
  // gamma 1.8 scaled to f^-1(128) = 1: (255/128)^1.8 at the top.
  EXPECT_NEAR(s.response->table[1][255], std::pow(255.0 / 128.0, 1.8), 0.02 * std::pow(255.0 / 128.0, 1.8));
  // Refusals: a folder that is not empty, nothing to resume, a bad spec, bad settings.
  r = RunCli("capture-sweep --source synthetic --out " + sweep);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("not empty"), std::string::npos) << r.output;
  r = RunCli("capture-sweep --resume --out " + (dir / "none").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("nothing to resume"), std::string::npos) << r.output;
  r = RunCli("capture-sweep --source synthetic:response=cubic --out " + (dir / "x").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("'cubic' is not a response"), std::string::npos) << r.output;
  r = RunCli("capture-sweep --repeats 0 --out " + (dir / "x").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("repeats"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "x"));
  // A capture record cut short (as if interrupted after 2 steps) is completed by --resume.
  {
    nlohmann::json rec = nlohmann::json::parse(test::ReadText(fs::path(sweep) / "capture.json"));
    const int steps = int(rec["exposures_ms"].size());
    rec["steps_done"] = 2;
    test::WriteText(fs::path(sweep) / "capture.json", rec.dump());
    r = RunCli("capture-sweep --resume --source synthetic:response=gamma1.8,size=128x96 --out " + sweep);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("2 of " + std::to_string(steps) + " steps were captured"), std::string::npos) << r.output;
    const io::SequenceReader seq(sweep, io::SequenceReadOptions{.allow_missing_depth = true});
    EXPECT_EQ(seq.size(), std::size_t(steps) * 4);
  }
}

TEST(Cli, CalibrateRefusesBadSweepsBeforeWritingAnything) {
  test::TempDir dir;
  const fs::path out = dir / "s.json";
  // Two frames, 1 and 2 ms: the curve would be off by more than half the range at the top.
  const std::string two = (dir / "two").string();
  ASSERT_EQ(RunCli("simulate --out " + two + " --sweep --sweep-exposures 1,2 --sweep-repeats 1 --size 96x72").status, 0);
  RunResult r = RunCli("calibrate " + two + " --out " + out.string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("2 distinct exposures"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("at least 3"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("response ("), std::string::npos) << "refused after fitting:\n" << r.output;
  EXPECT_FALSE(fs::exists(out));
  // An analog gain that changes across the sweep (exposure x gain held constant: it was read
  // and ignored, the curve 31-47 % off and judged good) or given for some frames only: refused
  // naming exposure.txt; a gain held fixed cancels out and calibrates.
  const fs::path gained = dir / "gained";
  ASSERT_EQ(RunCli("simulate --out " + gained.string() + " --sweep --sweep-exposures 1,2,4,8,16,32 --sweep-repeats 3 "
                   "--size 96x72").status, 0);
  AddGains(gained, [](int i) { return std::optional<double>(32.0 / double(1 << (i / 3))); });
  r = RunCli("calibrate " + gained.string() + " --out " + out.string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find((gained / "exposure.txt").string() + ": the analog gain changes across the sweep (1.000 to "
                          "32.000)"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
  ASSERT_EQ(RunCli("simulate --out " + (dir / "some").string() + " --sweep --sweep-exposures 1,2,4,8,16,32 "
                   "--sweep-repeats 3 --size 96x72").status, 0);
  AddGains(dir / "some", [](int i) { return i < 4 ? std::optional<double>(2.0) : std::nullopt; });
  r = RunCli("calibrate " + (dir / "some").string() + " --out " + out.string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("gives the analog gain for 4 of 18 frames"), std::string::npos) << r.output;
  ASSERT_EQ(RunCli("simulate --out " + (dir / "fixed").string() + " --sweep --sweep-exposures 1,2,4,8,16,32 "
                   "--sweep-repeats 3 --size 96x72").status, 0);
  AddGains(dir / "fixed", [](int) { return std::optional<double>(4.0); });
  r = RunCli("calibrate " + (dir / "fixed").string() + " --out " + (dir / "fixed.json").string());
  EXPECT_EQ(r.status, 0) << r.output;
  // Exposures listed in reverse: said so (not blamed on the output file), before the fit.
  const fs::path rev = dir / "rev";
  ASSERT_EQ(RunCli("simulate --out " + rev.string() + " --sweep --sweep-exposures 1,2,4,8,16,32 --sweep-repeats 3 "
                   "--size 96x72").status, 0);
  ReverseExposures(rev);
  r = RunCli("calibrate " + rev.string() + " --out " + out.string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("darker as the listed exposure grows"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("reverse"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(out.string()), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  // All white: every frame saturated.
  const std::string white = (dir / "white").string();
  ASSERT_EQ(RunCli("simulate --out " + white + " --sweep --sweep-exposures 2000,2800,4000,5600 --sweep-repeats 3 "
                   "--size 96x72").status, 0);
  r = RunCli("calibrate " + white + " --out " + out.string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("clipped"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  // A flat scene (a white wall): one brightness per exposure, most levels never seen.
  const fs::path flat = dir / "flat";
  fs::create_directories(flat / "rgb");
  std::ofstream rgb(flat / "rgb.txt"), exposure(flat / "exposure.txt");
  int frame = 0;
  for (double ms : {1.0, 2.0, 4.0, 8.0, 16.0, 32.0})
    for (int k = 0; k < 3; ++k, ++frame) {
      ColorImage im(96, 72);
      const int level = std::min(255, int(6 * ms)) ;
      for (std::size_t p = 0; p < im.size(); ++p) {
        const int v = std::clamp(level + int(p * 2654435761u % 5) - 2, 0, 255);
        im[p] = Rgb8{std::uint8_t(v), std::uint8_t(v), std::uint8_t(v)};
      }
      const std::string name = "rgb/" + std::to_string(frame) + ".png";
      io::WriteColorPng(flat / name, im);
      rgb << frame << " " << name << "\n";
      exposure << frame << " " << ms << "\n";
    }
  rgb.close();
  exposure.close();
  fs::copy_file(rev / "sensor.json", flat / "sensor.json");
  r = RunCli("calibrate " + flat.string() + " --out " + out.string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("too few distinct brightnesses"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  // A missing output folder: found before the sweep is even read.
  r = RunCli("calibrate " + rev.string() + " --out " + (dir / "no" / "such" / "s.json").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("does not exist"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("sweep "), std::string::npos) << "the sweep was read first:\n" << r.output;
}

TEST(Cli, CalibrateRefusesASweepWithoutExposures) {
  test::TempDir dir;
  const std::string sweep = (dir / "sweep").string();
  ASSERT_EQ(RunCli("simulate --out " + sweep + " --sweep --sweep-repeats 1 --size 32x24").status, 0);
  fs::remove(dir / "sweep" / "exposure.txt");
  const RunResult r = RunCli("calibrate " + sweep + " --out " + (dir / "s.json").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("exposure.txt"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("missing"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "s.json"));
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

// hdrfusion tonemap: every declared operator by key, parameters by key, PNG (display-encoded)
// or EXR (display-linear) out, the curve of a global operator; bad input refused, naming it.
TEST(Cli, TonemapEveryOperatorAndItsErrors) {
  test::TempDir dir;
  RadianceImage hdr(48, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 48; ++x) hdr(x, y) = Float3{1.f, 0.8f, 0.6f} * std::pow(10.f, float(x) / 12.f - 2);
  io::WriteExr(dir / "in.exr", hdr, io::ExrPrecision::kFloat);
  const std::string in = (dir / "in.exr").string();
  RunResult r = RunCli("tonemap --list");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* k : {"mantiuk08", "mantiuk06", "reinhard", "exposure", "linear", "preset=lcd_office", "temporal_hz"})
    EXPECT_NE(r.output.find(k), std::string::npos) << k;
  for (const char* op : {"mantiuk08", "mantiuk06", "reinhard", "exposure", "linear"}) {
    r = RunCli("tonemap " + in + " --op " + op + " --out " + (dir / (std::string(op) + ".png")).string());
    EXPECT_EQ(r.status, 0) << r.output;
    const ColorImage png = io::ReadColorImage(dir / (std::string(op) + ".png"));
    EXPECT_LT(png(2, 16).g, png(45, 16).g) << op;  // brighter stays brighter
  }
  r = RunCli("tonemap " + in + " --op mantiuk08 --set preset=crt --set contrast=1.2 --out " + (dir / "o.exr").string() +
             " --curve " + (dir / "curve.txt").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const RadianceImage lin = io::ReadExr(dir / "o.exr");
  EXPECT_GE(lin(0, 0).x, 0.f);
  EXPECT_LE(lin(47, 0).x, 1.f);
  EXPECT_NE(test::ReadText(dir / "curve.txt").find("log10_luminance display_linear"), std::string::npos);
  // Refusals, each naming what is wrong.
  r = RunCli("tonemap " + in + " --op mantiuk08 --set peak=5 --out " + (dir / "x.png").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("peak"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("[10, 10000]"), std::string::npos) << r.output;
  r = RunCli("tonemap " + in + " --op mantiuk08 --set gama=2 --out " + (dir / "x.png").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("gama"), std::string::npos) << r.output;
  r = RunCli("tonemap " + in + " --op durand --out " + (dir / "x.png").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("mantiuk08"), std::string::npos) << r.output;  // lists the known ones
  r = RunCli("tonemap " + in + " --op mantiuk06 --curve " + (dir / "c.txt").string() + " --out " + (dir / "x.png").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("local operator"), std::string::npos) << r.output;
  r = RunCli("tonemap " + in + " --view Filmic --out " + (dir / "x.png").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("Filmic"), std::string::npos) << r.output;
  r = RunCli("tonemap " + in + " --op linear --view Raw --out " + (dir / "raw.png").string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("sRGB / Raw"), std::string::npos) << r.output;
  r = RunCli("tonemap " + in + " --out " + (dir / "x.jpg").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find(".png or .exr"), std::string::npos) << r.output;
  r = RunCli("tonemap " + (dir / "missing.exr").string() + " --out " + (dir / "x.png").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("missing.exr"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

}  // namespace
}  // namespace hdrf

namespace hdrf {
namespace {

// hdrfusion export: a scan's mesh cleaned and levelled (floor at z = 0), the flags of the
// filled radiance in the PLY, the transform and the clean-up in export.json; refusals name
// what is wrong and write nothing.
TEST(Cli, ExportCleansAndLevelsAScan) {
  test::TempDir dir;
  RunResult r = RunCli("scan synthetic:frames=30,size=160x120 --out " + (dir / "scan").string());
  ASSERT_EQ(r.status, 0) << r.output;
  r = RunCli("export " + (dir / "scan").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::vector<std::uint8_t> flags;
  const mesh::Mesh m = io::ReadPly(dir / "out" / "mesh.ply", &flags);
  const auto report = nlohmann::json::parse(test::ReadText(dir / "out" / "export.json"));
  ASSERT_EQ(flags.size(), m.position.size());
  int flagged = 0;
  for (std::uint8_t f : flags) flagged += f;
  EXPECT_GE(flagged, report["clean"]["radiance_filled"].get<int>());
  EXPECT_EQ(report["vertices"].get<std::size_t>(), m.position.size());
  EXPECT_EQ(report["transform_output_from_model"].size(), 16u);
  ASSERT_TRUE(report["floor_found"].get<bool>()) << report.dump();
  // Level with the floor at 0: the 1st percentile of height is within 3 cm of it.
  std::vector<float> z;
  for (const Float3& p : m.position) z.push_back(p.z);
  std::sort(z.begin(), z.end());
  EXPECT_NEAR(z[z.size() / 100], 0.f, 0.03f);
  for (const Float3& c : m.radiance) ASSERT_GT(Luminance(c), 0.f);
  // To a triangle budget: within it, every vertex still with its radiance and normal, the
  // deviation reported.
  const std::size_t budget = m.triangles.size() / 5;
  r = RunCli("export " + (dir / "scan").string() + " --out " + (dir / "small").string() + " --triangles " + std::to_string(budget));
  ASSERT_EQ(r.status, 0) << r.output;
  const mesh::Mesh s = io::ReadPly(dir / "small" / "mesh.ply");
  const auto sr = nlohmann::json::parse(test::ReadText(dir / "small" / "export.json"));
  EXPECT_LE(s.triangles.size(), budget);
  EXPECT_GT(s.triangles.size(), budget / 2);
  EXPECT_LT(s.position.size(), m.position.size());
  for (std::size_t v = 0; v < s.position.size(); ++v) {
    ASSERT_GT(Luminance(s.radiance[v]), 0.f);
    ASSERT_NEAR(Length(s.normal[v]), 1.f, 1e-3);
  }
  EXPECT_GT(sr["simplify"]["error_m"].get<double>(), 0);
  EXPECT_LT(sr["simplify"]["error_m"].get<double>(), 0.01);
  // Refusals.
  r = RunCli("export " + (dir / "nothing").string() + " --out " + (dir / "x").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("nothing"), std::string::npos) << r.output;
  r = RunCli("export " + (dir / "scan").string() + " --out " + (dir / "x").string() + " --crop 0,0,0,1,1");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--crop"), std::string::npos) << r.output;
  // A clean-up that leaves nothing: said so, naming the setting, never a staging file.
  r = RunCli("export " + (dir / "scan").string() + " --out " + (dir / "x").string() + " --min-piece-area 1e9");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("nothing is left after the clean-up"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(".export-"), std::string::npos) << r.output;
  r = RunCli("export " + (dir / "scan").string() + " --out " + (dir / "x").string() + " --tone mantiuk08,peak=1");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("peak"), std::string::npos) << r.output;
  // A frame the scan does not have, with or without a render (the range is checked whether or
  // not a render is asked for): refused before any work, naming the range.
  for (const std::string frame : {"100000000", "30"})
    for (const std::string render : {"", " --render 64x48"}) {
      r = RunCli("export " + (dir / "scan").string() + " --out " + (dir / "x").string() + " --render-frame " + frame + render);
      EXPECT_EQ(r.status, 1) << frame << render << ": " << r.output;
      EXPECT_NE(r.output.find("30 poses (frames 0 to 29)"), std::string::npos) << r.output;
    }
  // A render the free memory cannot hold (16384x16384, the largest allowed, needs about
  // 28 GB): refused before any work, saying how much it needs.
  if (const auto free = AvailableHostBytes(); free && *free < 16384ull * 16384 * io::kRenderBytesPerPixel) {
    r = RunCli("export " + (dir / "scan").string() + " --out " + (dir / "x").string() + " --render 16384x16384");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("render needs about"), std::string::npos) << r.output;
  } else {
    std::printf("(the 16384x16384 render fits this machine's free memory: its refusal is not tried)\n");
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "x"));
  r = RunCli("export " + (dir / "scan").string() + " --out " + (dir / "last").string() + " --render-frame 29");
  EXPECT_EQ(r.status, 0) << r.output;
  // Into the scan's own folder (it replaced the raw mesh the next export bakes from): refused.
  const std::string raw = test::ReadText(dir / "scan" / "mesh.ply");
  for (const std::string out : {(dir / "scan").string(), (dir / "scan" / ".").string(), (dir / "scan" / "e").string()}) {
    r = RunCli("export " + (dir / "scan").string() + " --out " + out);
    EXPECT_EQ(r.status, 1) << out << ": " << r.output;
    EXPECT_NE(r.output.find("is the scan being exported"), std::string::npos) << r.output;
  }
  EXPECT_EQ(test::ReadText(dir / "scan" / "mesh.ply"), raw);
}

// The textured export end to end, read back by a third-party reader (assimp, where
// installed) and by OpenEXR; cancel and failure leave the output folder as it was.
std::string Field(const std::string& text, const std::string& key) {
  const auto at = text.find(key);
  if (at == std::string::npos) return "";
  const auto end = text.find('\n', at);
  return text.substr(at + key.size(), end - at - key.size());
}

TEST(Cli, ExportTexturedAssetsThatOtherToolsRead) {
  test::TempDir dir;
  RunResult r = RunCli("scan synthetic:frames=40,size=160x120 --out " + (dir / "scan").string());
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_TRUE(std::filesystem::exists(dir / "scan" / "keyframes.json"));
  const fs::path out = dir / "asset";
  r = RunCli("export " + (dir / "scan").string() + " --out " + out.string() + " --texel-mm 4 --render 200x150");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto rep = nlohmann::json::parse(test::ReadText(out / "export.json"));
  const auto& tex = rep["texture"];
  const long surface = tex["surface_texels"].get<long>(), frames = tex["texels_from_frames"].get<long>();
  const std::size_t tv = tex["textured_vertices"].get<std::size_t>(), tris = rep["triangles"].get<std::size_t>();
  std::printf("export: %zu textured vertices, %zu triangles, texture %dx%d, %ld of %ld texels from %d keyframes\n", tv, tris,
              tex["width"].get<int>(), tex["height"].get<int>(), frames, surface, tex["keyframes"].get<int>());
  EXPECT_GT(tex["keyframes"].get<int>(), 2);
  EXPECT_GT(double(frames), 0.3 * double(surface));  // (40 low-resolution frames: 6 keyframes)
  EXPECT_NEAR(tex["texel_mm"].get<double>(), 4.0, 1e-9);
  for (const char* f : {"mesh.ply", "mesh.obj", "mesh.mtl", "mesh_display.mtl", "mesh.glb", "texture.exr", "texture.png",
                        "render.exr", "render.png", "export.json"})
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  // The HDR texture and the render read back with OpenEXR: units in the header, alpha and depth.
  const RadianceImage t = io::ReadExr(out / "texture.exr");
  EXPECT_EQ(t.width(), tex["width"].get<int>());
  EXPECT_NE(io::ReadExrAttribute(out / "texture.exr", "hdrfusion:units").value_or("").find("radiance"), std::string::npos);
  const Image<float> alpha = io::ReadExrChannel(out / "render.exr", "A"), depth = io::ReadExrChannel(out / "render.exr", "Z");
  ASSERT_EQ(alpha.width(), 200);
  ASSERT_EQ(depth.height(), 150);
  long covered = 0, consistent = 0;
  for (std::size_t i = 0; i < alpha.size(); ++i) {
    covered += alpha[i] == 1.0f;
    consistent += (alpha[i] == 1.0f) == (depth[i] > 0.1f && depth[i] < 20.0f);
  }
  EXPECT_GT(covered, long(alpha.size() / 4));
  EXPECT_EQ(consistent, long(alpha.size()));
  // A third-party reader: assimp's command-line tool.
  if (std::system("command -v assimp > /dev/null 2>&1") != 0) {
    std::printf("assimp not installed (Debian's assimp-utils): skipping the third-party read-back\n");
  } else {
    const auto info = [&](const std::string& file) {
      const std::string log = (dir / "assimp.txt").string();
      const int rc = std::system(("assimp info '" + (out / file).string() + "' > '" + log + "' 2>&1").c_str());
      EXPECT_EQ(rc, 0) << file;
      return test::ReadText(log);
    };
    const std::string obj = info("mesh.obj"), glb = info("mesh.glb");
    EXPECT_EQ(std::stoul(Field(obj, "Faces:")), tris) << obj;
    EXPECT_EQ(std::stoul(Field(glb, "Faces:")), tris) << glb;
    EXPECT_EQ(std::stoul(Field(glb, "Vertices:")), tv) << glb;
    // assimp's OBJ reader makes a vertex of every face corner and joins identical ones again:
    // exactly our vertices. (`assimp info` computes tangents before joining, and keeps apart
    // the corners whose tangents differ where the UV map bends at a chart's edge: a few more.)
    const std::string joined = (dir / "joined.ply").string();
    ASSERT_EQ(std::system(("assimp export '" + (out / "mesh.obj").string() + "' '" + joined + "' -fply -jiv > '" +
                           (dir / "assimp_export.txt").string() + "' 2>&1").c_str()),
              0);
    const std::string ply = test::ReadText(joined);
    const std::size_t at = ply.find("element vertex ");
    ASSERT_NE(at, std::string::npos);
    EXPECT_EQ(std::stoul(ply.substr(at + 15)), tv);
    const std::size_t obj_vertices = std::stoul(Field(obj, "Vertices:"));
    EXPECT_GE(obj_vertices, tv);
    EXPECT_LE(double(obj_vertices), 1.03 * double(tv));
    EXPECT_NE(obj.find("'texture.exr'"), std::string::npos) << obj;
    EXPECT_NE(Field(glb, "Textures (embed.):").find('1'), std::string::npos) << glb;
  }
  // Cancelled midway: nothing in the output folder changes.
  const io::ScanData scan = io::LoadScan(dir / "scan");
  io::AssetOptions o;
  o.atlas.texel_m = 0.004;
  const fs::path fresh = dir / "cancelled";
  std::filesystem::create_directories(fresh);
  test::WriteText(fresh / "keep.txt", "mine");
  for (const char* at : {"texture", "writing"}) {
    EXPECT_THROW(io::ExportAsset(scan, o, fresh, [at](const std::string& stage, double) { return stage != at; }), Cancelled);
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(fresh)) names.push_back(e.path().filename().string());
    EXPECT_EQ(names, std::vector<std::string>{"keep.txt"}) << "cancelled at " << at;
  }
  // A file that cannot be replaced: refused before any file moves; the old export stays whole.
  std::filesystem::remove(out / "mesh.glb");
  std::filesystem::create_directory(out / "mesh.glb");
  const auto before = std::filesystem::last_write_time(out / "mesh.obj");
  r = RunCli("export " + (dir / "scan").string() + " --out " + out.string() + " --texel-mm 4");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("mesh.glb"), std::string::npos) << r.output;
  EXPECT_EQ(std::filesystem::last_write_time(out / "mesh.obj"), before);
  for (const auto& e : std::filesystem::directory_iterator(out))
    EXPECT_NE(e.path().filename().string().rfind(".export-", 0), 0u) << "staging left behind: " << e.path();
  // Refusals naming the option.
  r = RunCli("export " + (dir / "scan").string() + " --out " + (dir / "y").string() + " --formats ply,fbx");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("fbx"), std::string::npos) << r.output;
  r = RunCli("export " + (dir / "scan").string() + " --out " + (dir / "y").string() + " --texel-mm 0.01");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("mm"), std::string::npos) << r.output;
  r = RunCli("export " + (dir / "scan").string() + " --out " + (dir / "y").string() + " --sample-sigma 5");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--sample-sigma"), std::string::npos) << r.output;
  r = RunCli("export " + (dir / "scan").string() + " --out " + (dir / "y").string() + " --render 640x");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--render"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "y"));
}

}  // namespace
}  // namespace hdrf
