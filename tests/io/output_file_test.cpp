// How outputs are written (io/output_file.h): never through a planted name, never over a
// device or a link, never half; and a set of outputs all or nothing.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <set>

#include "common/error.h"
#include "io/output_file.h"
#include "io/ply.h"
#include "io/tum.h"
#include "support/test_support.h"

namespace hdrf::io {
namespace {

namespace fs = std::filesystem;
using test::ExpectErrorContaining;
using test::ReadText;
using test::TempDir;
using test::WriteText;

mesh::Mesh Triangle() {
  mesh::Mesh m;
  m.position = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.normal = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  m.radiance = {{1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
  m.triangles = {{0, 1, 2}};
  return m;
}

// The name a writer used to stage to (".NAME.partial.EXT"): a link planted there sent the
// bytes into another file. Now the staging name is random and created exclusively.
TEST(OutputFile, StagingNamesAreUnpredictableAndALinkAtTheOldNameIsNotFollowed) {
  TempDir dir;
  WriteText(dir / "victim.txt", "precious");
  fs::create_symlink(dir / "victim.txt", dir / ".mesh.partial.ply");
  WritePly(dir / "mesh.ply", Triangle());
  EXPECT_EQ(ReadText(dir / "victim.txt"), "precious");
  EXPECT_EQ(ReadPly(dir / "mesh.ply").triangles.size(), 1u);
  // Two writers of one target at once stage to different, unguessable names.
  std::set<std::string> names;
  {
    OutputFile a(dir / "t.txt"), b(dir / "t.txt");
    for (const fs::path& p : test::StagingFiles(dir.path())) names.insert(p.filename().string());
    EXPECT_EQ(names.size(), 2u);
    for (const std::string& n : names) {
      EXPECT_EQ(n.rfind(".t.txt.", 0), 0u) << n;
      EXPECT_GE(n.size(), std::string(".t.txt.").size() + 12 + std::string(".partial").size()) << n;
    }
  }
  // Neither committed: nothing is left behind, and no target was made.
  EXPECT_TRUE(test::StagingFiles(dir.path()).empty());
  EXPECT_FALSE(fs::exists(dir / "t.txt"));
}

// Names up to the file system's 255 bytes are written: the staging name beside them is
// shortened (it added 22 bytes, and a 234-byte name failed at the end of the work).
TEST(OutputFile, NamesUpToTheFileSystemsLimitAreWritten) {
  TempDir dir;
  for (std::size_t n : {233u, 234u, 255u}) {
    const std::string name = std::string(n - 4, 'a') + ".txt";
    WriteFileAtomically(dir / name, "content");
    EXPECT_EQ(ReadText(dir / name), "content") << n;
  }
  // Shortened staging names are still recognised as staging names.
  {
    OutputFile f(dir / (std::string(251, 'b') + ".txt"));
    const std::vector<fs::path> staged = test::StagingFiles(dir.path());
    ASSERT_EQ(staged.size(), 1u);
    EXPECT_LE(staged[0].filename().string().size(), 255u);
  }
  EXPECT_TRUE(test::StagingFiles(dir.path()).empty());
}

TEST(OutputFile, TargetsThatAreNotRegularFilesAreRefusedAndKept) {
  TempDir dir;
  WriteText(dir / "victim.txt", "precious");
  // A link at the target: neither written through nor replaced.
  fs::create_symlink(dir / "victim.txt", dir / "trajectory.txt");
  ExpectErrorContaining([&] { WriteTrajectory(dir / "trajectory.txt", {{0.0, Pose::Identity()}}); },
                        {(dir / "trajectory.txt").string(), "symbolic link"});
  EXPECT_TRUE(fs::is_symlink(dir / "trajectory.txt"));
  EXPECT_EQ(ReadText(dir / "victim.txt"), "precious");
  // A pipe (as a device node would be): refused, still a pipe.
  ASSERT_EQ(::mkfifo((dir / "mesh.ply").c_str(), 0644), 0);
  ExpectErrorContaining([&] { WritePly(dir / "mesh.ply", Triangle()); },
                        {(dir / "mesh.ply").string(), "not a regular file"});
  EXPECT_TRUE(fs::is_fifo(dir / "mesh.ply"));
  fs::create_directory(dir / "report.json");
  ExpectErrorContaining([&] { WriteFileAtomically(dir / "report.json", "{}"); }, {"report.json", "is a folder"});
  EXPECT_TRUE(test::StagingFiles(dir.path()).empty());
}

TEST(OutputFile, WrittenWithTheUsualPermissionsAndAFullDiskLeavesTheOldFile) {
  TempDir dir;
  WriteFileAtomically(dir / "a.txt", "old");
  const mode_t mask = ::umask(0);
  ::umask(mask);
  struct stat st {};
  ASSERT_EQ(::stat((dir / "a.txt").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0666u & ~mask);
  {
    const test::FileSizeLimit full(1000);
    ExpectErrorContaining([&] { WriteFileAtomically(dir / "a.txt", std::string(5000, 'x')); },
                          {(dir / "a.txt").string(), "disk full"});
  }
  EXPECT_EQ(ReadText(dir / "a.txt"), "old");
  EXPECT_TRUE(test::StagingFiles(dir.path()).empty());
}

TEST(OutputSet, ASetIsMovedIntoPlaceWholeOrNotAtAll) {
  TempDir dir;
  WriteText(dir / "a.txt", "old a");
  WriteText(dir / "b.txt", "old b");
  // Left without Commit (an error while writing): nothing changed, nothing left.
  {
    OutputSet set;
    WriteFileAtomically(dir / "a.txt", "new a");
    EXPECT_EQ(ReadText(dir / "a.txt"), "old a");  // waits for the set
    EXPECT_EQ(test::StagingFiles(dir.path()).size(), 1u);
  }
  EXPECT_EQ(ReadText(dir / "a.txt"), "old a");
  EXPECT_TRUE(test::StagingFiles(dir.path()).empty());
  // The disk fills at the second file: the first is not replaced either.
  try {
    OutputSet set;
    WriteFileAtomically(dir / "a.txt", "new a");
    const test::FileSizeLimit full(1000);
    WriteFileAtomically(dir / "b.txt", std::string(5000, 'b'));
    set.Commit();
    ADD_FAILURE() << "the second write should have failed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("b.txt"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ReadText(dir / "a.txt"), "old a");
  EXPECT_EQ(ReadText(dir / "b.txt"), "old b");
  // A target turned into something else before the set moves: refused before any file moves.
  {
    OutputSet set;
    WriteFileAtomically(dir / "a.txt", "new a");
    WriteFileAtomically(dir / "b.txt", "new b");
    fs::remove(dir / "b.txt");
    fs::create_directory(dir / "b.txt");
    ExpectErrorContaining([&] { set.Commit(); }, {"b.txt", "is a folder"});
  }
  EXPECT_EQ(ReadText(dir / "a.txt"), "old a");
  fs::remove(dir / "b.txt");
  // Committed, with a set opened inside it (it joins the outer one).
  {
    OutputSet set;
    WriteFileAtomically(dir / "a.txt", "new a");
    {
      OutputSet inner;
      WriteFileAtomically(dir / "b.txt", "new b");
      inner.Commit();
    }
    EXPECT_FALSE(fs::exists(dir / "b.txt"));
    set.Commit();
  }
  EXPECT_EQ(ReadText(dir / "a.txt"), "new a");
  EXPECT_EQ(ReadText(dir / "b.txt"), "new b");
  EXPECT_TRUE(test::StagingFiles(dir.path()).empty());
  // No set is left open on the thread: the next file goes straight into place.
  WriteFileAtomically(dir / "c.txt", "c");
  EXPECT_EQ(ReadText(dir / "c.txt"), "c");
}

// Messages carry text from input files (names, quoted fields): control characters and
// bytes that are not UTF-8 are shown escaped, never sent to the terminal.
TEST(Printable, ControlCharactersAndBrokenUtf8AreEscaped) {
  EXPECT_EQ(Printable("plain: ok"), "plain: ok");
  EXPECT_EQ(Printable("a\x1b[2Jb"), "a\\x1b[2Jb");
  EXPECT_EQ(Printable("line\nbreak\r\tand\x7f"), "line\\x0abreak\\x0d\\x09and\\x7f");
  EXPECT_EQ(Printable("gr\xc3\xbc\xc3\x9f"), "gr\xc3\xbc\xc3\x9f");         // UTF-8 kept
  EXPECT_EQ(Printable("csi \xc2\x9b" "31m"), "csi \\xc2\\x9b31m");           // C1 control
  EXPECT_EQ(Printable("raw \x9b" "31m"), "raw \\x9b31m");                    // not UTF-8
  EXPECT_EQ(Printable("cut \xe2\x82"), "cut \\xe2\\x82");                    // truncated
  EXPECT_EQ(Printable("long \xc0\xaf"), "long \\xc0\\xaf");                  // overlong
  EXPECT_EQ(Printable("\xe2\x82\xac \xf0\x9f\x93\xb7"), "\xe2\x82\xac \xf0\x9f\x93\xb7");
  const InputError e("bad\x1b]0;title\x07name.png", 3, "cannot parse '\x1b[31m'");
  EXPECT_EQ(std::string(e.what()), "bad\\x1b]0;title\\x07name.png:3: cannot parse '\\x1b[31m'");
  EXPECT_EQ(Printable(Printable("x\x01y")), Printable("x\x01y"));
}

}  // namespace
}  // namespace hdrf::io
