// The scan job (core/jobs/scan_job.h) that `hdrfusion scan` and the studio both run: its
// recovery file, its project, a continued scan's source, and the output set.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "common/error.h"
#include "io/project.h"
#include "io/source_spec.h"
#include "jobs/scan_job.h"

namespace hdrf {
namespace {

namespace fs = std::filesystem;

// A folder of its own, with the recovery files (XDG state home) inside it.
struct Scratch {
  fs::path dir;
  Scratch() {
    dir = fs::temp_directory_path() / ("hdrf-job-" + std::to_string(::getpid()) + "-" +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    ::setenv("XDG_STATE_HOME", (dir / "state").c_str(), 1);
  }
  ~Scratch() { fs::remove_all(dir); }
};

const std::string kSpec = "synthetic:frames=16,size=160x120,seed=3";

void Scan(jobs::ScanJob& job, pipeline::FrameSource& src, int frames) {
  pipeline::FrameInput f;
  for (int i = 0; i < frames && src.Next(f); ++i) job.Process(f);
}

TEST(ScanJob, AutosavesSavesAndOnClosingKeepsOnlyWhatWasNotSaved) {
  Scratch s;
  auto src = io::OpenSource(kSpec, "");
  jobs::ScanJob job(pipeline::PipelineOptions{}, src->sensor(), "job", 0);
  job.SetSource(src->description(), kSpec);
  EXPECT_EQ(job.recovery_file().parent_path(), s.dir / "state" / "hdrfusion" / "recovery");
  EXPECT_EQ(job.Autosave(true), "") << "nothing scanned: nothing to save";
  EXPECT_FALSE(fs::exists(job.recovery_file()));
  Scan(job, *src, 5);
  // Autosaves every 0 s means never, unless forced.
  EXPECT_EQ(job.Autosave(), "");
  EXPECT_FALSE(fs::exists(job.recovery_file()));
  EXPECT_EQ(job.Autosave(true), "");
  const io::Project autosaved = io::LoadProject(job.recovery_file());
  EXPECT_EQ(autosaved.resume.frames, 5);
  EXPECT_FALSE(autosaved.finished);
  EXPECT_EQ(autosaved.source_spec, kSpec);
  EXPECT_EQ(autosaved.source, src->description());
  // Saved by the user: the recovery file is gone, the project finished.
  const fs::path project = s.dir / "p.hdrproj";
  job.Save(project, true);
  EXPECT_FALSE(fs::exists(job.recovery_file()));
  EXPECT_TRUE(io::LoadProject(project).finished);
  job.Close();
  EXPECT_FALSE(fs::exists(job.recovery_file())) << "everything was saved";
  // Frames the user did not save are autosaved on closing.
  Scan(job, *src, 2);
  job.Close();
  ASSERT_TRUE(fs::exists(job.recovery_file()));
  EXPECT_EQ(io::LoadProject(job.recovery_file()).resume.frames, 7);
}

TEST(ScanJob, AContinuedScanGoesOnAfterItsFramesAsIfItNeverStopped) {
  Scratch s;
  auto whole_src = io::OpenSource(kSpec, "");
  jobs::ScanJob whole(pipeline::PipelineOptions{}, whole_src->sensor(), "whole", 0);
  Scan(whole, *whole_src, 16);

  auto first_src = io::OpenSource(kSpec, "");
  jobs::ScanJob first(pipeline::PipelineOptions{}, first_src->sensor(), "first", 0);
  first.SetSource(first_src->description(), kSpec);
  Scan(first, *first_src, 9);
  const fs::path project = s.dir / "p.hdrproj";
  first.Save(project, false);
  const io::Project p = io::LoadProject(project);

  jobs::ScanJob next(p, nullptr, "next", 0);
  EXPECT_EQ(next.continued_frames(), 9);
  EXPECT_EQ(next.session().frames(), 9);
  auto again = io::OpenSource(kSpec, "");
  EXPECT_EQ(next.Continue(p, *again, kSpec), jobs::ContinueFrom::kAfterScanned);
  EXPECT_TRUE(next.same_source());
  Scan(next, *again, 16);
  ASSERT_EQ(next.session().frames(), 16);
  for (int i : {9, 12, 15}) {
    const Pose& a = whole.session().reports()[std::size_t(i)].T_world_camera;
    const Pose& b = next.session().reports()[std::size_t(i)].T_world_camera;
    EXPECT_LT((a.matrix() - b.matrix()).norm(), 1e-9) << "frame " << i;
  }

  // Another scene of the same camera goes on from its first frame; another camera cannot.
  const std::string other = "synthetic:frames=16,size=160x120,seed=4";
  auto other_src = io::OpenSource(other, "");
  jobs::ScanJob from_other(p, nullptr, "other", 0);
  EXPECT_EQ(from_other.Continue(p, *other_src, other), jobs::ContinueFrom::kFirstFrame);
  EXPECT_FALSE(from_other.same_source());
  auto small = io::OpenSource("synthetic:frames=16,size=80x60,seed=3", "");
  jobs::ScanJob from_small(p, nullptr, "small", 0);
  EXPECT_EQ(from_small.Continue(p, *small, "synthetic:frames=16,size=80x60,seed=3"), jobs::ContinueFrom::kOtherCamera);
}

// A project named near the 255-byte limit: its recovery file (named after it) and its
// outputs are still written (both failed, and the scan was lost).
TEST(ScanJob, AProjectNamedNearTheLimitKeepsItsRecoveryFile) {
  Scratch s;
  auto src = io::OpenSource(kSpec, "");
  // 99 bytes, a two-byte UTF-8 character across the 100-byte cut, 150 more: the character is
  // not split.
  const std::string stem = std::string(99, 'p') + "\xc3\xa9" + std::string(150, 'p');
  jobs::ScanJob job(pipeline::PipelineOptions{}, src->sensor(), stem, 0);
  EXPECT_LE(job.recovery_file().filename().string().size(), 255u);
  EXPECT_EQ(job.recovery_file().filename().string().rfind(std::string(99, 'p') + "-", 0), 0u)
      << job.recovery_file().filename();
  Scan(job, *src, 3);
  EXPECT_EQ(job.Autosave(true), "");
  EXPECT_EQ(io::LoadProject(job.recovery_file()).resume.frames, 3);
  const fs::path project = s.dir / (std::string(247, 'q') + ".hdrproj");
  job.Save(project, true);
  EXPECT_EQ(io::LoadProject(project).resume.frames, 3);
}

TEST(ScanJob, OutputsAreOneSetAndAFailureKeepsTheModelInTheRecoveryFile) {
  Scratch s;
  auto src = io::OpenSource(kSpec, "");
  jobs::ScanJob job(pipeline::PipelineOptions{}, src->sensor(), "out", 0);
  job.SetSource(src->description(), kSpec);
  Scan(job, *src, 8);
  const tonemap::OperatorDecl& tone = tonemap::FindOperator("mantiuk08");
  const tonemap::Params params = tonemap::ResolveParams(tone, {});

  // A project that cannot be written: nothing in the output folder, the model kept.
  const fs::path out = s.dir / "out";
  fs::create_directories(out);
  std::ofstream(s.dir / "file") << "x";
  try {
    job.WriteOutputs(out, s.dir / "file" / "p.hdrproj", tone, params, 1.0);
    FAIL() << "a project under a file was written";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("nothing in " + out.string() + " was changed"), std::string::npos) << what;
    EXPECT_NE(what.find("kept in " + job.recovery_file().string()), std::string::npos) << what;
  }
  EXPECT_TRUE(fs::is_empty(out));
  ASSERT_TRUE(fs::exists(job.recovery_file()));
  EXPECT_EQ(io::LoadProject(job.recovery_file()).resume.frames, 8);

  // Written: the whole set, the report counting every frame, the recovery file gone.
  std::vector<std::string> said;
  const jobs::OutputSummary w =
      job.WriteOutputs(out, out / "scan.hdrproj", tone, params, 1.0, [&](const std::string& m) { said.push_back(m); });
  EXPECT_GT(w.triangles, 1000u);
  for (const char* f : {"trajectory.txt", "mesh.ply", "report.json", "keyframes.json", "sensor.json", "render_first.exr",
                        "render_last.png", "render_last_normals.png", "scan.hdrproj"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  std::ifstream in(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["frames"], 8);
  EXPECT_EQ(report["frames_detail"].size(), 8u);
  EXPECT_EQ(report["mesh"]["triangles"], w.triangles);
  EXPECT_EQ(report["source"], src->description());
  EXPECT_FALSE(fs::exists(job.recovery_file()));
  ASSERT_EQ(said.size(), 2u);
  EXPECT_EQ(said[1], "extracting the mesh...");

  // An output that may not be replaced is refused before any work.
  fs::create_directories(s.dir / "blocked" / "mesh.ply");
  EXPECT_THROW(jobs::ScanJob::CheckOutputs(s.dir / "blocked", s.dir / "blocked" / "scan.hdrproj", kSpec), Error);
  EXPECT_NO_THROW(jobs::ScanJob::CheckOutputs(out, out / "scan.hdrproj", kSpec));
  // OUT/keyframes a link to another folder (the keyframes were written through it, over
  // that folder's files): refused before the scan, the folder untouched.
  fs::create_directories(s.dir / "victim");
  std::ofstream(s.dir / "victim" / "000000.png") << "precious";
  fs::create_directories(s.dir / "linked");
  fs::create_directory_symlink(s.dir / "victim", s.dir / "linked" / "keyframes");
  try {
    jobs::ScanJob::CheckOutputs(s.dir / "linked", s.dir / "linked" / "scan.hdrproj", kSpec);
    ADD_FAILURE() << "a keyframes folder that is a link was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("keyframes: is a symbolic link"), std::string::npos) << e.what();
  }
  std::ifstream victim(s.dir / "victim" / "000000.png");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(victim), {}), "precious");
  // Outputs that are the recording read (however the path is written) are refused.
  EXPECT_THROW(jobs::ScanJob::CheckOutputs(s.dir / "out" / "." , s.dir / "p.hdrproj", out.string()), InputError);
  EXPECT_THROW(jobs::ScanJob::CheckOutputs(s.dir / "x", out / "scan.hdrproj", (out / "scan.hdrproj").string()),
               InputError);
}

// Every failed scan leaves a recovery file: a new job removes those older than 30 days and
// those beyond the newest 20, and says so; a recovery file being resumed stays.
TEST(ScanJob, RecoveryFilesOfOldScansArePrunedWithANotice) {
  Scratch s;
  auto src = io::OpenSource(kSpec, "");
  jobs::ScanJob first(pipeline::PipelineOptions{}, src->sensor(), "first", 0);
  Scan(first, *src, 3);
  ASSERT_EQ(first.Autosave(true), "");
  EXPECT_EQ(first.notice(), "");
  const fs::path folder = first.recovery_file().parent_path();
  const auto now = fs::file_time_type::clock::now();
  // The autosave 40 days old (it is resumed below), 3 other files as old, 22 of the last days.
  fs::last_write_time(first.recovery_file(), now - std::chrono::hours(24 * 40));
  for (int i = 0; i < 25; ++i) {
    const fs::path f = folder / ("scan-" + std::to_string(i) + ".hdrproj");
    std::ofstream(f) << std::string(1000, 'x');
    fs::last_write_time(f, now - std::chrono::hours(i < 22 ? i + 1 : 24 * 31 + i));
  }
  const io::Project resumed = io::LoadProject(first.recovery_file());
  jobs::ScanJob next(resumed, nullptr, "next", 0);
  EXPECT_TRUE(fs::exists(first.recovery_file())) << "the file being resumed was removed";
  // Kept: the newest 20 of the 22 recent ones; removed: their 2 oldest and the 3 old ones.
  for (int i = 0; i < 25; ++i)
    EXPECT_EQ(fs::exists(folder / ("scan-" + std::to_string(i) + ".hdrproj")), i < 20) << i;
  EXPECT_NE(next.notice().find("removed 5 recovery files of earlier unfinished scans ("), std::string::npos)
      << next.notice();
  EXPECT_NE(next.notice().find(" from " + folder.string() + ": older than 30 days"), std::string::npos) << next.notice();
  // No longer resumed, the old autosave goes too; then there is nothing to say.
  jobs::ScanJob third(pipeline::PipelineOptions{}, src->sensor(), "third", 0);
  EXPECT_NE(third.notice().find("removed 1 recovery files of"), std::string::npos) << third.notice();
  EXPECT_FALSE(fs::exists(first.recovery_file()));
  jobs::ScanJob fourth(pipeline::PipelineOptions{}, src->sensor(), "fourth", 0);
  EXPECT_EQ(fourth.notice(), "");
}

}  // namespace
}  // namespace hdrf
