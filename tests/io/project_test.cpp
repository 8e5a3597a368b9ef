// Project files: a scan saved and resumed goes on exactly as if it had never stopped; damaged,
// truncated and newer files are refused naming the problem; a failed save keeps the earlier one.
#include <gtest/gtest.h>

#include <cstring>

#include <algorithm>

#include <cstdio>
#include <fstream>

#include "common/error.h"
#include "io/project.h"
#include "mesh/mesh.h"
#include "pipeline/scan_session.h"
#include "sim/synthetic_source.h"
#include "support/sim_frames.h"
#include "support/test_support.h"

namespace hdrf {
namespace {

namespace fs = std::filesystem;

struct Scan {
  std::vector<Pose> poses;
  mesh::Mesh mesh;
  std::size_t keyframes = 0;
};

const SensorInfo& Sensor() {
  static const SensorInfo s = sim::SyntheticSource(sim::SimOptions()).sensor();
  return s;
}

Scan Finish(pipeline::ScanSession& s) {
  return {s.poses(), s.pipeline().ExtractMesh(), s.keyframes().size()};
}

double MaxPoseDifference(const std::vector<Pose>& a, const std::vector<Pose>& b) {
  double d = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    d = std::max(d, (a[i].translation() - b[i].translation()).norm());
  return d;
}

std::size_t MeshDifferences(const mesh::Mesh& a, const mesh::Mesh& b) {
  if (a.position.size() != b.position.size() || a.triangles.size() != b.triangles.size())
    return std::max(a.position.size(), b.position.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.position.size(); ++i) {
    const Float3 p = a.position[i], q = b.position[i];
    n += p.x != q.x || p.y != q.y || p.z != q.z;
    if (i < a.radiance.size() && i < b.radiance.size()) {
      const Float3 r = a.radiance[i], s = b.radiance[i];
      n += r.x != s.x || r.y != s.y || r.z != s.z;
    }
  }
  for (std::size_t i = 0; i < a.triangles.size(); ++i) n += a.triangles[i] != b.triangles[i];
  return n;
}

// Runs `frames` through one session, or the first `split` through one, saves it, reopens the
// file into a fresh session and runs the rest there.
Scan ScanFrames(const std::vector<sim::SimFrame>& frames, const pipeline::PipelineOptions& o, int split, const fs::path& file) {
  auto s = std::make_unique<pipeline::ScanSession>(o, Sensor().camera, Sensor());
  for (int i = 0; i < int(frames.size()); ++i) {
    if (i == split) {
      io::SaveProject(file, *s, {"test", "", false});
      const io::Project p = io::LoadProject(file);
      EXPECT_EQ(p.resume.frames, split);
      EXPECT_EQ(p.model.allocated_bricks(), s->pipeline().volume_stats().allocated_bricks);
      // The verification's history and the relocalisation views come back as they were.
      const pipeline::ResumePoint rp = s->pipeline().resume_point();
      EXPECT_EQ(p.resume.anchored, rp.anchored);
      EXPECT_EQ(p.resume.residuals, rp.residuals);
      EXPECT_EQ(p.resume.photo_residuals, rp.photo_residuals);
      EXPECT_EQ(p.resume.exposure_drifts, rp.exposure_drifts);
      EXPECT_FALSE(rp.reloc.empty());
      // Where the last ray cast's rays started (near the fused frame's depth) comes back too.
      EXPECT_FALSE(rp.raycast_guide.empty());
      EXPECT_EQ(p.resume.raycast_guide.width(), rp.raycast_guide.width());
      EXPECT_EQ(p.resume.raycast_guide.height(), rp.raycast_guide.height());
      std::size_t guide_differ = 0, guided = 0;
      for (std::size_t j = 0; j < std::min(rp.raycast_guide.size(), p.resume.raycast_guide.size()); ++j) {
        guide_differ += p.resume.raycast_guide[j] != rp.raycast_guide[j];
        guided += rp.raycast_guide[j] > 0;
      }
      EXPECT_EQ(guide_differ, 0u);
      EXPECT_GT(guided, rp.raycast_guide.size() / 4);
      EXPECT_EQ(p.resume.reloc.size(), rp.reloc.size());
      for (std::size_t k = 0; k < std::min(p.resume.reloc.size(), rp.reloc.size()); ++k) {
        const pipeline::RelocEntry &a = p.resume.reloc[k], &b = rp.reloc[k];
        EXPECT_EQ(a.frame, b.frame);
        EXPECT_LT((a.T_world_camera.matrix() - b.T_world_camera.matrix()).norm(), 1e-12);
        EXPECT_EQ(a.code.depth, b.code.depth);
        EXPECT_EQ(a.code.shade, b.code.shade);
        EXPECT_EQ(a.code.lit, b.code.lit);
        EXPECT_EQ(a.thumbnail.size(), b.thumbnail.size());
        std::size_t differ = 0;
        for (std::size_t j = 0; j < std::min(a.thumbnail.size(), b.thumbnail.size()); ++j) differ += !(a.thumbnail[j] == b.thumbnail[j]);
        EXPECT_EQ(differ, 0u) << "thumbnail " << k;
      }
      s = io::ResumeSession(p);
      EXPECT_EQ(s->pipeline().relocaliser().entries().size(), rp.reloc.size());
    }
    s->Process(test::AsInput(frames[std::size_t(i)]));
  }
  return Finish(*s);
}

// The built-in room, 300 flicker frames at the default settings: saved after 150 and resumed
// for the remaining 150, the trajectory and the mesh are those of one 300-frame scan.
TEST(Project, SavedAfter150AndResumedIsTheSameAsOneScan) {
  test::TempDir dir;
  const auto frames = test::Frames(300, sim::AeMode::kFlicker);
  const pipeline::PipelineOptions o;
  const Scan whole = ScanFrames(frames, o, -1, {});
  const Scan resumed = ScanFrames(frames, o, 150, dir / "half.hdrproj");
  ASSERT_EQ(resumed.poses.size(), 300u);
  const double dpose = MaxPoseDifference(whole.poses, resumed.poses);
  const std::size_t dmesh = MeshDifferences(whole.mesh, resumed.mesh);
  std::printf("resumed after 150 of 300 frames: max trajectory difference %.3g mm, %zu mesh values differ (of %zu "
              "vertices), keyframes %zu and %zu; project file %.1f MiB\n",
              1000 * dpose, dmesh, whole.mesh.position.size(), whole.keyframes, resumed.keyframes,
              double(fs::file_size(dir / "half.hdrproj")) / (1 << 20));
  EXPECT_LE(dpose, 0.001);
  EXPECT_EQ(dmesh, 0u);
  EXPECT_GT(whole.mesh.triangles.size(), 100000u);
  EXPECT_EQ(whole.keyframes, resumed.keyframes);
}

// Frame-to-frame tracking keeps its reference (the last tracked frame) in the project.
TEST(Project, FrameToFrameScanResumesWithItsReferenceFrame) {
  test::TempDir dir;
  const auto frames = test::Frames(40, sim::AeMode::kFlicker);
  pipeline::PipelineOptions o;
  o.tracker.frame_to_model = false;
  o.tracker.kind = tracking::TrackerKind::kNr;
  const Scan whole = ScanFrames(frames, o, -1, {});
  const Scan resumed = ScanFrames(frames, o, 20, dir / "f2f.hdrproj");
  const double dpose = MaxPoseDifference(whole.poses, resumed.poses);
  std::printf("frame to frame, resumed after 20 of 40: max trajectory difference %.3g mm\n", 1000 * dpose);
  EXPECT_LE(dpose, 0.001);
  EXPECT_EQ(MeshDifferences(whole.mesh, resumed.mesh), 0u);
}

TEST(Project, DamagedTruncatedAndNewerFilesAreRefusedNamingTheProblem) {
  test::TempDir dir;
  const auto frames = test::Frames(4, sim::AeMode::kFlicker);
  pipeline::ScanSession s(pipeline::PipelineOptions{}, Sensor().camera, Sensor());
  for (const auto& f : frames) s.Process(test::AsInput(f));
  const fs::path good = dir / "good.hdrproj";
  io::SaveProject(good, s, {"test", "synthetic:frames=4", true});
  const io::Project p = io::LoadProject(good);
  EXPECT_TRUE(p.finished);
  EXPECT_EQ(p.source, "test");
  EXPECT_EQ(p.source_spec, "synthetic:frames=4");
  EXPECT_EQ(p.reports.size(), 4u);
  // How firmly the frame fixed its pose (information along its weakest and strongest
  // directions) and how far from the prediction, kept per frame.
  EXPECT_GT(p.reports[3].tracking.weakest_info, 0);
  EXPECT_EQ(p.reports[3].tracking.weakest_info, s.reports()[3].tracking.weakest_info);
  EXPECT_EQ(p.reports[3].tracking.strongest_info, s.reports()[3].tracking.strongest_info);
  EXPECT_EQ(p.reports[3].tracking.prior_sigmas, s.reports()[3].tracking.prior_sigmas);
  EXPECT_EQ(p.keyframes.size(), s.keyframes().size());
  EXPECT_EQ(p.model.allocated_bricks(), s.pipeline().volume_stats().allocated_bricks);
  const std::string bytes = test::ReadText(good);
  // Truncated anywhere: refused, naming the file.
  for (const double at : {0.001, 0.3, 0.999}) {
    const fs::path f = dir / "cut.hdrproj";
    test::WriteText(f, bytes.substr(0, std::size_t(double(bytes.size()) * at)));
    test::ExpectErrorContaining([&] { io::LoadProject(f); }, {"cut.hdrproj"});
  }
  test::WriteText(dir / "cut.hdrproj", bytes.substr(0, bytes.size() - 16));  // the end marker gone
  test::ExpectErrorContaining([&] { io::LoadProject(dir / "cut.hdrproj"); }, {"cut.hdrproj", "truncated"});
  // One byte changed inside the voxels: the chunk's CRC names it.
  std::string damaged = bytes;
  damaged[bytes.size() / 2] = char(damaged[bytes.size() / 2] ^ 0x5a);
  test::WriteText(dir / "bad.hdrproj", damaged);
  test::ExpectErrorContaining([&] { io::LoadProject(dir / "bad.hdrproj"); }, {"bad.hdrproj", "damaged", "CRC"});
  // The ray cast's start guide with a depth out of range (its CRC made right): refused, naming
  // the file and the guide.
  {
    const std::size_t at = bytes.find("RCGD");
    ASSERT_NE(at, std::string::npos);
    std::uint64_t size = 0;
    std::memcpy(&size, bytes.data() + at + 4, 8);
    ASSERT_GE(size, 4u);
    std::string bad_guide = bytes;
    const float negative = -1.f;
    std::memcpy(bad_guide.data() + at + 16, &negative, 4);
    std::uint32_t crc = 0xffffffffu;  // CRC-32 (the zlib polynomial) of the payload
    for (std::size_t i = 0; i < size; ++i) {
      crc ^= std::uint8_t(bad_guide[at + 16 + i]);
      for (int b = 0; b < 8; ++b) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    crc ^= 0xffffffffu;
    std::memcpy(bad_guide.data() + at + 12, &crc, 4);
    test::WriteText(dir / "guide.hdrproj", bad_guide);
    test::ExpectErrorContaining([&] { io::LoadProject(dir / "guide.hdrproj"); }, {"guide.hdrproj", "start guide"});
  }
  // A newer format version, another file, no file.
  std::string newer = bytes;
  newer[8] = 99;
  test::WriteText(dir / "newer.hdrproj", newer);
  test::ExpectErrorContaining([&] { io::LoadProject(dir / "newer.hdrproj"); }, {"version 99", "newer HDRFusion"});
  test::WriteText(dir / "other.hdrproj", "ply\nformat ascii 1.0\n");
  test::ExpectErrorContaining([&] { io::LoadProject(dir / "other.hdrproj"); }, {"other.hdrproj", "not an HDRFusion project"});
  test::ExpectErrorContaining([&] { io::LoadProject(dir / "none.hdrproj"); }, {"none.hdrproj", "file is missing"});
  // The source it came from: the same spec; another auto exposure is another source.
  EXPECT_TRUE(io::SameSource(p, "synthetic:frames=4", "anything"));
  EXPECT_FALSE(io::SameSource(p, "synthetic:frames=4,ae=smooth", "anything"));
  // Resuming with settings that change the model is refused, saying why.
  test::ExpectErrorContaining(
      [&] { io::ResumeSession(p, [](pipeline::PipelineOptions& o) { o.volume.voxel_m = 0.01f; }); },
      {"good.hdrproj", "10.000000 mm", "project's own settings"});
}

// A save that cannot finish (here: the disk fills halfway) leaves the earlier save intact
// and readable, and no partial file behind.
TEST(Project, AFailedSaveKeepsTheEarlierSave) {
  test::TempDir dir;
  const auto frames = test::Frames(6, sim::AeMode::kFlicker);
  pipeline::ScanSession s(pipeline::PipelineOptions{}, Sensor().camera, Sensor());
  for (int i = 0; i < 3; ++i) s.Process(test::AsInput(frames[std::size_t(i)]));
  const fs::path file = dir / "sub" / "scan.hdrproj";
  io::SaveProject(file, s, {"test", "", false});
  const std::string before = test::ReadText(file);
  for (int i = 3; i < 6; ++i) s.Process(test::AsInput(frames[std::size_t(i)]));
  {
    const test::FileSizeLimit full(before.size() / 2);
    test::ExpectErrorContaining([&] { io::SaveProject(file, s, {"test", "", false}); },
                                {file.string(), "disk full"});
  }
  EXPECT_TRUE(test::StagingFiles(dir.path()).empty());
  EXPECT_EQ(test::ReadText(file), before);
  EXPECT_EQ(io::LoadProject(file).resume.frames, 3);
}

}  // namespace
}  // namespace hdrf
