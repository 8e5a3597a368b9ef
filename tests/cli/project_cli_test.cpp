// hdrfusion scan --save / --resume / --autosave, and export and eval reading a project, run as
// a user runs them; and a scan killed mid-save (kill -9) leaves a recovery file that opens and
// resumes.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "io/output_file.h"
#include "io/project.h"
#include "io/ply.h"
#include "io/tum.h"
#include "support/test_support.h"

namespace hdrf {
namespace {

namespace fs = std::filesystem;
using RunResult = test::CommandResult;

RunResult RunCli(const std::string& args) { return test::RunCommand(std::string(HDRF_CLI) + " " + args); }

// Autosaves of these tests go to their own folder, not the user's.
class ProjectCli : public ::testing::Test {
 protected:
  void SetUp() override {
    state_ = std::make_unique<test::TempDir>();
    setenv("XDG_STATE_HOME", state_->path().c_str(), 1);
  }
  void TearDown() override { unsetenv("XDG_STATE_HOME"); }
  std::unique_ptr<test::TempDir> state_;
};

TEST_F(ProjectCli, SaveResumeExportAndEval) {
  test::TempDir dir;
  const std::string seq = (dir / "seq").string();
  ASSERT_EQ(RunCli("simulate --out " + seq + " --frames 60 --size 160x120 --ae flicker").status, 0);
  RunResult r = RunCli("scan " + seq + " --out " + (dir / "whole").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "whole" / "scan.hdrproj")) << r.output;
  // Half, saved to a named project; then the rest, resumed from it.
  const std::string half = (dir / "half.hdrproj").string();
  r = RunCli("scan " + seq + " --out " + (dir / "a").string() + " --frames 30 --save " + half);
  ASSERT_EQ(r.status, 0) << r.output;
  // The same folder, its path written another way: it goes on after the frames scanned.
  r = RunCli("scan --resume " + half + " " + (dir / "." / "seq").string() + "/ --out " + (dir / "b").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("after its 30 frames"), std::string::npos) << r.output;
  const auto whole = io::ReadTrajectory(dir / "whole" / "trajectory.txt");
  const auto resumed = io::ReadTrajectory(dir / "b" / "trajectory.txt");
  ASSERT_EQ(whole.size(), 60u);
  ASSERT_EQ(resumed.size(), 60u);
  double d = 0;
  for (std::size_t i = 0; i < whole.size(); ++i) {
    EXPECT_EQ(whole[i].timestamp, resumed[i].timestamp);
    d = std::max(d, (whole[i].T_world_camera.translation() - resumed[i].T_world_camera.translation()).norm());
  }
  EXPECT_LE(d, 0.001);
  EXPECT_EQ(test::ReadText(dir / "whole" / "mesh.ply"), test::ReadText(dir / "b" / "mesh.ply"));
  // Export and eval read the project.
  r = RunCli("export " + (dir / "b" / "scan.hdrproj").string() + " --out " + (dir / "asset").string() +
             " --formats ply,gltf --texel-mm 8");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "asset" / "mesh.glb"));
  r = RunCli("eval " + seq + " " + (dir / "b" / "scan.hdrproj").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto ev = nlohmann::json::parse(test::ReadText(dir / "b" / "scan.eval.json"));
  EXPECT_EQ(ev["pairs"].get<int>(), 60);
  EXPECT_LT(ev["ate_rmse_m"].get<double>(), 0.05);
  EXPECT_GT(ev["mesh_vertices"].get<int>(), 1000);
  // A project does not go on with another camera.
  const std::string small = (dir / "small").string();
  ASSERT_EQ(RunCli("simulate --out " + small + " --frames 4 --size 64x48").status, 0);
  r = RunCli("scan --resume " + half + " " + small + " --out " + (dir / "c").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("half.hdrproj"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("160x120 camera"), std::string::npos) << r.output;
  // Nor through another response: the same recording with its calibration taken away,
  // read as sRGB, would fuse radiance in other units into the same model.
  const std::string uncal = (dir / "uncal").string();
  fs::copy(seq, uncal, fs::copy_options::recursive);
  {
    auto j = nlohmann::json::parse(test::ReadText(fs::path(uncal) / "sensor.json"));
    j.erase("response");
    test::WriteText(fs::path(uncal) / "sensor.json", j.dump(2));
  }
  r = RunCli("scan --resume " + half + " " + uncal + " --response srgb --out " + (dir / "c").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("another camera response"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("half.hdrproj"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "c" / "trajectory.txt"));
  // Nor with settings that change its model.
  r = RunCli("scan --resume " + half + " " + seq + " --out " + (dir / "c").string() + " --voxel-size 0.01");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("project's own settings"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("half.hdrproj"), std::string::npos) << r.output;
  // Finished scans leave no recovery file.
  EXPECT_TRUE(io::FindRecoveryFiles().empty());
}

// A memory budget too small for the room: the scan says so once, goes on, keeps the model,
// and the project exports.
TEST_F(ProjectCli, BudgetReachedIsSaidAndTheModelIsKeptAndExports) {
  test::TempDir dir;
  RunResult r = RunCli("scan synthetic:frames=20,size=160x120 --out " + (dir / "s").string() +
                       " --volume.max_memory_mb 2");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string said = "the volume is full: the model reached its memory budget of 2 MiB";
  const std::size_t at = r.output.find(said);
  EXPECT_NE(at, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(said, at + 1), std::string::npos) << "said more than once:\n" << r.output;
  const auto rep = nlohmann::json::parse(test::ReadText(dir / "s" / "report.json"));
  EXPECT_TRUE(rep["volume"]["full"].get<bool>());
  EXPECT_EQ(rep["frames"].get<int>(), 20);
  EXPECT_LE(rep["volume"]["bytes"].get<double>(), 2.02 * (1 << 20));
  r = RunCli("export " + (dir / "s" / "scan.hdrproj").string() + " --out " + (dir / "e").string() +
             " --formats ply --no-texture");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "e" / "mesh.ply"));
  // A ray cast that reaches 1 m while the room is 1-4 m away: said once, with the share.
  r = RunCli("scan synthetic:frames=10,size=160x120 --out " + (dir / "f").string() +
             " --volume.raycast_far_m 1 --autosave 0");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string far = "of the depth lies beyond 1.0 m, past the model's ray cast";
  const std::size_t at_far = r.output.find(far);
  EXPECT_NE(at_far, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(far, at_far + 1), std::string::npos) << r.output;
  const auto rep_far = nlohmann::json::parse(test::ReadText(dir / "f" / "report.json"));
  EXPECT_GT(rep_far["frames_detail"][0]["depth_beyond_far"].get<double>(), 0.5);
}

pid_t Spawn(const std::string& command, const std::string& log = "/dev/null") {
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", ("exec " + command + " >" + log + " 2>&1").c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

// kill -9 while autosaving (an autosave after every frame; the kill sent while the partial
// file of the next save exists): the earlier recovery file always opens, and resumes.
TEST_F(ProjectCli, KilledMidSaveLeavesARecoveryFileThatOpensAndResumes) {
  test::TempDir dir;
  const std::string spec = "synthetic:frames=400,size=160x120";
  int mid_save = 0, opened = 0;
  fs::path last, kept;  // the last recovery file seen, and where it was moved meanwhile
  for (int attempt = 0; attempt < 6 && mid_save < 2; ++attempt) {
    const pid_t pid = Spawn(std::string(HDRF_CLI) + " scan " + spec + " --out " + (dir / "k").string() +
                            " --autosave 0.0001");
    // Until the first autosave exists; then until the next one is being written (its
    // partial file exists), and kill it there.
    const auto t0 = std::chrono::steady_clock::now();
    const auto waited = [&] { return std::chrono::steady_clock::now() - t0 > std::chrono::seconds(60); };
    while (io::FindRecoveryFiles().empty() && !waited()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    std::this_thread::sleep_for(std::chrono::milliseconds(37 * attempt));
    // The staging files beside the recovery files (an autosave being written).
    const auto staging = [&] {
      std::vector<fs::path> found;
      std::error_code ec;
      for (const auto& e : fs::directory_iterator(io::RecoveryFolder(), ec))
        if (io::IsStagingFile(e.path())) found.push_back(e.path());
      return found;
    };
    const auto partial = [&] { return !staging().empty(); };
    while (!partial() && !waited()) std::this_thread::sleep_for(std::chrono::microseconds(100));
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the scan ended before it was killed";
    const std::vector<fs::path> left = staging();
    for (const fs::path& f : left) fs::remove(f);
    for (const fs::path& f : io::FindRecoveryFiles()) {
      if (!left.empty()) ++mid_save;
      const io::Project p = io::LoadProject(f);  // throws (and fails the test) if unreadable
      EXPECT_FALSE(p.finished);
      EXPECT_GT(p.resume.frames, 0);
      ++opened;
      last = f;
      kept = dir / ("seen-" + std::to_string(opened) + ".hdrproj");
      fs::rename(f, kept);
    }
  }
  std::printf("%d recovery files opened after kill -9; %d of the kills landed mid-save\n", opened, mid_save);
  EXPECT_GE(mid_save, 1);
  ASSERT_GE(opened, 1);
  // The next scan offers the recovery file; resuming it goes on after its frames.
  fs::rename(kept, last);
  RunResult r = RunCli("scan " + spec + " --out " + (dir / "other").string() + " --frames 2 --autosave 0");
  EXPECT_NE(r.output.find("unfinished scan was autosaved to " + last.string()), std::string::npos) << r.output;
  const int frames = io::LoadProject(last).resume.frames;
  r = RunCli("scan --resume " + last.string() + " " + spec + " --out " + (dir / "r").string() + " --frames 5");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("after its " + std::to_string(frames) + " frames"), std::string::npos) << r.output;
  EXPECT_EQ(io::ReadTrajectory(dir / "r" / "trajectory.txt").size(), std::size_t(frames + 5));
}

// Every regular file under `dir` (links skipped) with its bytes.
std::map<std::string, std::string> Snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && !e.is_symlink()) files[fs::relative(e.path(), dir).string()] = test::ReadText(e.path());
  return files;
}

// A scan that fails (the source midway, a full disk, an output that may not be replaced) or
// is cancelled (Ctrl-C) leaves the previous outputs exactly as they were; where it got far
// enough, its model is kept in the recovery file, which exports.
TEST_F(ProjectCli, AFailedOrCancelledScanChangesNoOutputAndKeepsTheModel) {
  test::TempDir dir;
  const fs::path seq = dir / "seq", out = dir / "out";
  ASSERT_EQ(RunCli("simulate --out " + seq.string() + " --frames 12 --size 80x60").status, 0);
  RunResult r = RunCli("scan " + seq.string() + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto before = Snapshot(out);
  ASSERT_GE(before.size(), 10u);
  std::size_t biggest = 0, total = 0;
  for (const auto& [name, bytes] : before) {
    biggest = std::max(biggest, bytes.size());
    total += bytes.size();
  }
  // 1. A frame missing midway (the 7th colour image).
  fs::copy(seq, dir / "broken", fs::copy_options::recursive);
  std::vector<fs::path> rgb;
  for (const auto& e : fs::directory_iterator(dir / "broken" / "rgb")) rgb.push_back(e.path());
  std::sort(rgb.begin(), rgb.end());
  fs::remove(rgb[6]);
  r = RunCli("scan " + (dir / "broken").string() + " --out " + out.string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(rgb[6].filename().string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("nothing in " + out.string() + " was changed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the 6 frames scanned are kept in"), std::string::npos) << r.output;
  EXPECT_EQ(Snapshot(out), before);
  std::vector<fs::path> kept = io::FindRecoveryFiles();
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_NE(r.output.find("hdrfusion export " + kept[0].string()), std::string::npos) << r.output;
  const io::Project p = io::LoadProject(kept[0]);
  EXPECT_EQ(p.resume.frames, 6);
  EXPECT_FALSE(p.finished);
  r = RunCli("export " + kept[0].string() + " --out " + (dir / "e").string() + " --formats ply --no-texture");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_GT(io::ReadPly(dir / "e" / "mesh.ply").triangles.size(), 100u);
  fs::remove(kept[0]);
  // 2. The disk fills while the outputs are written: some are complete by then, none moves.
  r = test::RunCommand(test::WithFileSizeLimit(biggest / 2, std::string(HDRF_CLI) + " scan " + seq.string() +
                                                                " --out " + out.string()));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("disk full"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("nothing in " + out.string() + " was changed"), std::string::npos) << r.output;
  EXPECT_EQ(Snapshot(out), before);
  EXPECT_TRUE(test::StagingFiles(out).empty());
  EXPECT_LT(biggest / 2, total - biggest) << "the limit must let other outputs complete first";
  for (const fs::path& f : io::FindRecoveryFiles()) fs::remove(f);
  // 3. A link planted at an output: refused, neither followed nor replaced.
  test::WriteText(dir / "victim.txt", "precious");
  fs::remove(out / "mesh.ply");
  fs::create_symlink(dir / "victim.txt", out / "mesh.ply");
  r = RunCli("scan " + seq.string() + " --out " + out.string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find((out / "mesh.ply").string() + ": is a symbolic link"), std::string::npos) << r.output;
  EXPECT_EQ(test::ReadText(dir / "victim.txt"), "precious");
  auto without_mesh = before;
  without_mesh.erase("mesh.ply");
  EXPECT_EQ(Snapshot(out), without_mesh);
  fs::remove(out / "mesh.ply");
  for (const fs::path& f : io::FindRecoveryFiles()) fs::remove(f);
  // 4. Ctrl-C once the scan has autosaved: exit status 130, outputs unchanged, model kept.
  const pid_t pid = Spawn(std::string(HDRF_CLI) + " scan synthetic:frames=1000,size=80x60 --out " + out.string() +
                          " --autosave 0.2");
  const auto t0 = std::chrono::steady_clock::now();
  while (io::FindRecoveryFiles().empty() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_EQ(Snapshot(out), without_mesh);
  kept = io::FindRecoveryFiles();
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_GT(io::LoadProject(kept[0]).resume.frames, 0);
  fs::remove(kept[0]);
  // 5. SIGTERM while the mesh is extracted (the process ended at once: no message, no
  // recovery file, the finished scan lost and its staged outputs left behind): the writing
  // stops, nothing in the output folder changes, the model is kept.
  const fs::path log = dir / "term.log";
  const pid_t term = Spawn(std::string(HDRF_CLI) + " scan synthetic:frames=30,size=160x120 --volume.voxel_m 0.003 --out " +
                               out.string(),
                           log.string());
  const auto t1 = std::chrono::steady_clock::now();
  while (test::ReadText(log).find("extracting the mesh") == std::string::npos &&
         std::chrono::steady_clock::now() - t1 < std::chrono::seconds(120))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(term, SIGTERM);
  waitpid(term, &status, 0);
  const std::string said = test::ReadText(log);
  ASSERT_TRUE(WIFEXITED(status)) << said;
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM) << said;
  EXPECT_NE(said.find("cancelled by SIGTERM while writing the outputs: nothing in " + out.string() + " was changed; "
                      "the 30 frames scanned are kept in"),
            std::string::npos)
      << said;
  EXPECT_EQ(Snapshot(out), without_mesh);
  EXPECT_TRUE(test::StagingFiles(out).empty());
  kept = io::FindRecoveryFiles();
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(io::LoadProject(kept[0]).resume.frames, 30);
}

}  // namespace
}  // namespace hdrf
