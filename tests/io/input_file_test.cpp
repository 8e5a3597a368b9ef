// Limits on what is read (common/input_file.h): sizes from headers before decoding, file sizes,
// special files, paths that leave the sequence folder.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <filesystem>
#include <limits>
#include <cstring>
#include <fstream>

#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>

#include "common/error.h"
#include "io/exr.h"
#include "io/image_io.h"
#include "io/json_file.h"
#include "io/ply.h"
#include "io/sensor_json.h"
#include "io/sequence.h"
#include "io/sweep.h"
#include "io/tum.h"
#include "support/test_support.h"

namespace hdrf::io {
namespace {

namespace fs = std::filesystem;
using test::ExpectErrorContaining;
using test::TempDir;

long PeakRssKib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

// A valid small PNG whose header is then made to claim w x h (the pixel data stays small).
void WriteLyingPng(const fs::path& file, std::uint32_t w, std::uint32_t h) {
  WriteColorPng(file, ColorImage(8, 8));
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  const unsigned char be[8] = {std::uint8_t(w >> 24), std::uint8_t(w >> 16), std::uint8_t(w >> 8), std::uint8_t(w),
                               std::uint8_t(h >> 24), std::uint8_t(h >> 16), std::uint8_t(h >> 8), std::uint8_t(h)};
  f.seekp(16);
  f.write(reinterpret_cast<const char*>(be), 8);
}

// A 3-frame 64x48 sequence.
void WriteSequence(const fs::path& folder) {
  SensorInfo sensor;
  sensor.camera = {64, 48, 50, 50, 31.5f, 23.5f};
  sensor.depth_scale = 5000;
  SequenceWriter w(folder, sensor);
  const ColorImage color(64, 48);
  DepthRawImage depth(64, 48);
  for (std::size_t i = 0; i < depth.size(); ++i) depth[i] = 10000;
  for (int i = 0; i < 3; ++i) w.Add(i / 30.0, color, &depth, 10.0, Pose::Identity(), nullptr);
}

TEST(InputLimits, ImageSizesAreCheckedFromTheHeaderBeforeDecoding) {
  TempDir dir;
  WriteLyingPng(dir / "huge.png", 30000, 30000);
  EXPECT_LT(fs::file_size(dir / "huge.png"), 1000u);
  const long before = PeakRssKib();
  ExpectErrorContaining([&] { ReadColorImage(dir / "huge.png"); },
                        {(dir / "huge.png").string(), "claims 30000x30000 pixels, more than this program reads"});
  // In a sequence, a frame of the wrong size is refused from its header: 16000x16000 is
  // within the program's limits but would cost 2.3 GB to decode.
  WriteSequence(dir / "seq");
  const SequenceReader seq(dir / "seq");
  ASSERT_EQ(seq.ReadFrame(1).color.width(), 64);
  WriteLyingPng(seq.frames()[1].color_path, 16000, 16000);
  ExpectErrorContaining([&] { seq.ReadFrame(1); },
                        {seq.frames()[1].color_path.string(), "image is 16000x16000 but sensor.json says 64x48"});
  const long grew_mib = (PeakRssKib() - before) / 1024;
  std::printf("peak memory grew by %ld MiB while refusing both images\n", grew_mib);
  EXPECT_LT(grew_mib, 64);
  // A header too short to be a PNG's is named as such.
  test::WriteText(dir / "cut.png", std::string("\x89PNG\r\n\x1a\n\0\0", 10));
  ExpectErrorContaining([&] { ReadColorImage(dir / "cut.png"); }, {"cut.png", "without its header"});
}

// A TIFF claiming 16000x16000 pixels in a few hundred bytes.
void WriteLyingTiff(const fs::path& file, std::uint32_t w, std::uint32_t h) {
  std::string b = "II*";
  b += '\0';
  const auto u16 = [&](std::uint32_t v) { b += char(v & 255), b += char(v >> 8 & 255); };
  const auto u32 = [&](std::uint32_t v) { u16(v & 0xffff), u16(v >> 16); };
  u32(8);
  const std::uint32_t tags[][4] = {{256, 4, 1, w}, {257, 4, 1, h}, {258, 3, 1, 16}, {277, 3, 1, 1}};
  u16(4);
  for (const auto& t : tags) {
    u16(t[0]), u16(t[1]), u32(t[2]);
    if (t[1] == 3) u16(t[3]), u16(0);
    else u32(t[3]);
  }
  u32(0);
  b += std::string(64, '\0');
  test::WriteText(file, b);
}

// Every path that reads frames sizes them from their header first: a sweep (calibrate,
// merge) and a depth frame in TIFF, as a sequence's colour frame already is; and an image
// in a format whose header is not read is refused rather than decoded.
TEST(InputLimits, EveryFramePathSizesItsImagesFromTheHeader) {
  TempDir dir;
  WriteSequence(dir / "seq");
  const SequenceReader seq(dir / "seq");
  const long before = PeakRssKib();
  // A sweep (the sequence layout with exposures) whose second frame claims 16000x16000.
  WriteLyingPng(seq.frames()[1].color_path, 16000, 16000);
  ExpectErrorContaining([&] { ReadSweep(dir / "seq"); },
                        {seq.frames()[1].color_path.string(), "image is 16000x16000 but sensor.json says 64x48"});
  // A TIFF depth frame claiming the same.
  WriteLyingTiff(dir / "depth.tif", 16000, 16000);
  ExpectErrorContaining([&] { ReadDepthImage(dir / "depth.tif", [](int w, int h) {
                          if (w != 64 || h != 48) throw InputError("depth.tif", "image is " + std::to_string(w) + "x" +
                                                                                    std::to_string(h));
                        }); },
                        {"depth.tif", "image is 16000x16000"});
  const long grew_mib = (PeakRssKib() - before) / 1024;
  std::printf("peak memory grew by %ld MiB while refusing both images\n", grew_mib);
  EXPECT_LT(grew_mib, 64);
  // A format whose header is not read (BMP) is not decoded.
  test::WriteText(dir / "x.bmp", "BM" + std::string(100, '\0'));
  ExpectErrorContaining([&] { ReadColorImage(dir / "x.bmp"); }, {"x.bmp", "is not a PNG, JPEG or TIFF image"});
}

TEST(InputLimits, SpecialFilesAndPathsOutsideTheSequenceAreRefused) {
  TempDir dir;
  WriteSequence(dir / "seq");
  // A pipe where an image should be: refused at once, not waited on.
  ASSERT_EQ(::mkfifo((dir / "seq" / "rgb" / "pipe.png").c_str(), 0644), 0);
  ExpectErrorContaining([&] { ReadColorImage(dir / "seq" / "rgb" / "pipe.png"); }, {"pipe.png", "not a regular file"});
  ExpectErrorContaining([&] { ReadColorImage("/dev/zero"); }, {"/dev/zero", "not a regular file"});
  ExpectErrorContaining([&] { ReadJsonFile(dir / "seq"); }, {"is a folder"});
  // Lists that leave the sequence folder.
  const std::string good = test::ReadText(dir / "seq" / "rgb.txt");
  for (const std::string& bad : {"/dev/zero", "../../etc/passwd", "rgb/../../x.png"}) {
    std::string list = good;
    const std::size_t at = list.find("rgb/", list.rfind('#') == std::string::npos ? 0 : list.find('\n', list.rfind('#')));
    ASSERT_NE(at, std::string::npos);
    list.replace(at, list.find('\n', at) - at, bad);
    test::WriteText(dir / "seq" / "rgb.txt", list);
    ExpectErrorContaining([&] { SequenceReader s(dir / "seq"); }, {"rgb.txt:", "'" + bad + "' leaves the sequence folder"});
  }
  test::WriteText(dir / "seq" / "rgb.txt", good);
  // A 100 MB sensor.json (sparse: it costs no disk) is refused unread.
  const fs::path big = dir / "seq" / "sensor.json";
  fs::resize_file(big, 100u << 20);
  const long before = PeakRssKib();
  ExpectErrorContaining([&] { ReadSensorJson(big); }, {big.string(), "is 100 MiB, more than the 64 MiB"});
  EXPECT_LT((PeakRssKib() - before) / 1024, 16);
}

// A mesh whose values are damaged (an infinite position, a negative radiance: a bit flip
// in a float) is refused naming the vertex, not carried on into every export.
TEST(InputLimits, DamagedMeshValuesAreRefused) {
  TempDir dir;
  mesh::Mesh m;
  m.position = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.normal = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  m.radiance = {{1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
  m.triangles = {{0, 1, 2}};
  WritePly(dir / "good.ply", m);
  ASSERT_EQ(ReadPly(dir / "good.ply").position.size(), 3u);
  const std::string good = test::ReadText(dir / "good.ply");
  const std::size_t data = good.find("end_header\n") + 11;
  const std::size_t record = (good.size() - data - 13) / 3;  // three vertices, one face
  const auto patched = [&](std::size_t vertex, std::size_t offset, float v) {
    std::string b = good;
    std::memcpy(&b[data + vertex * record + offset], &v, 4);
    test::WriteText(dir / "bad.ply", b);
  };
  patched(1, 0, std::numeric_limits<float>::infinity());
  ExpectErrorContaining([&] { ReadPly(dir / "bad.ply"); }, {"bad.ply", "vertex 1", "position or normal"});
  patched(2, 16, std::numeric_limits<float>::quiet_NaN());  // a normal
  ExpectErrorContaining([&] { ReadPly(dir / "bad.ply"); }, {"bad.ply", "vertex 2", "position or normal"});
  patched(0, 27, -5.0f);  // radiance_r
  ExpectErrorContaining([&] { ReadPly(dir / "bad.ply"); }, {"bad.ply", "vertex 0", "radiance that is negative"});
}

TEST(InputLimits, MeshAndOpenExrHeadersThatClaimTooMuchAreRefused) {
  TempDir dir;
  test::WriteText(dir / "m.ply",
                  "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\n"
                  "property float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                  "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float radiance_r\n"
                  "property float radiance_g\nproperty float radiance_b\nelement face 0\n"
                  "property list uchar int vertex_indices\nend_header\n");
  ExpectErrorContaining([&] { ReadPly(dir / "m.ply"); }, {"m.ply", "is not a count this file can hold"});
  std::string ply = test::ReadText(dir / "m.ply");
  ply.replace(ply.find("1000000000000"), 13, "100");
  test::WriteText(dir / "m.ply", ply);
  ExpectErrorContaining([&] { ReadPly(dir / "m.ply"); }, {"m.ply", "claims 100 vertices and 0 faces, more than"});
  ply.replace(ply.find("vertex 100"), 10, "vertex 1e2");
  test::WriteText(dir / "m.ply", ply);
  ExpectErrorContaining([&] { ReadPly(dir / "m.ply"); }, {"m.ply:3", "element count '1e2'"});
  // An OpenEXR image 70000 pixels wide (one row: small on disk).
  {
    Imf::Header h(70000, 1);
    h.channels().insert("R", Imf::Channel(Imf::HALF));
    h.channels().insert("G", Imf::Channel(Imf::HALF));
    h.channels().insert("B", Imf::Channel(Imf::HALF));
    std::vector<half> px(70000, half(1.0f));
    Imf::FrameBuffer fb;
    for (const char* c : {"R", "G", "B"})
      fb.insert(c, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(px.data()), sizeof(half), 0));
    Imf::OutputFile out((dir / "wide.exr").c_str(), h);
    out.setFrameBuffer(fb);
    out.writePixels(1);
  }
  ExpectErrorContaining([&] { ReadExr(dir / "wide.exr"); }, {"wide.exr", "claims 70000x1 pixels"});
  // A 1x1 image whose header is patched to claim 16000x16000 (within the pixel limit): the
  // file cannot hold the offsets of that many scan lines, so it is refused from the header,
  // before OpenEXR allocates anything for it.
  {
    WriteExr(dir / "claims.exr", RadianceImage(1, 1, Float3{1, 1, 1}));
    std::string exr = test::ReadText(dir / "claims.exr");
    const std::string key("dataWindow\0box2i\0", 17);
    const std::size_t at = exr.find(key);
    ASSERT_NE(at, std::string::npos);
    for (int k : {2, 3}) {  // max.x, max.y (little-endian int32 after the 4-byte size)
      const std::uint32_t v = 15999;
      for (int byte = 0; byte < 4; ++byte) exr[at + key.size() + 4 + 4 * std::size_t(k) + std::size_t(byte)] = char(v >> (8 * byte));
    }
    test::WriteText(dir / "claims.exr", exr);
  }
  const long before = PeakRssKib();
  for (int i = 0; i < 3; ++i) {
    ExpectErrorContaining([&] { ReadExr(dir / "claims.exr"); }, {"claims.exr", "too short for the 16000x16000 image"});
    ExpectErrorContaining([&] { ReadExrChannel(dir / "claims.exr", "Z"); }, {"claims.exr", "too short"});
  }
  EXPECT_LT((PeakRssKib() - before) / 1024, 16);
  // An attribute claiming 1.7 GB in a 600-byte file (found by the fuzzer: OpenEXR allocated
  // it before reading), in a multi-part file as well as a single-part one.
  for (const std::uint32_t version : {2u, 2u | 0x1000u}) {
    std::string exr = test::ReadText(dir / "wide.exr").substr(0, 600);
    for (int byte = 0; byte < 4; ++byte) exr[4 + std::size_t(byte)] = char(version >> (8 * byte));
    const std::size_t at = exr.find(std::string("channels\0chlist\0", 16)) + 16;
    const std::uint32_t claim = 0x696c6863u;
    for (int byte = 0; byte < 4; ++byte) exr[at + std::size_t(byte)] = char(claim >> (8 * byte));
    test::WriteText(dir / "claim.exr", exr);
    const long before_claim = PeakRssKib();
    ExpectErrorContaining([&] { ReadExr(dir / "claim.exr"); }, {"claim.exr", "an attribute running past the end"});
    ExpectErrorContaining([&] { ReadExrAttribute(dir / "claim.exr", "x"); }, {"claim.exr", "running past the end"});
    EXPECT_LT((PeakRssKib() - before_claim) / 1024, 16);
  }
  // A type name longer than OpenEXR reads (31 bytes): it would take the name's tail for the
  // attribute's size (another fuzzer input, claiming 1.8 GB that way).
  {
    std::string exr = test::ReadText(dir / "wide.exr");
    const std::size_t at = exr.find(std::string("compression\0compression\0", 24));
    ASSERT_NE(at, std::string::npos);
    exr.insert(at + 12 + 4, std::string(40, '\xff'));
    test::WriteText(dir / "longname.exr", exr);
    ExpectErrorContaining([&] { ReadExr(dir / "longname.exr"); }, {"longname.exr", "a name too long"});
  }
  // A data window whose origin lies 2^30 pixels away (found by the fuzzer: the first pixel's
  // offset overflowed the address space, UBSan) is refused; an ordinary offset window reads
  // back pixel for pixel.
  {
    WriteExr(dir / "far.exr", RadianceImage(1, 1, Float3{1, 1, 1}));
    std::string exr = test::ReadText(dir / "far.exr");
    const std::string key("dataWindow\0box2i\0", 17);
    const std::size_t at = exr.find(key) + key.size() + 4;
    for (int k : {1, 3}) {  // min.y and max.y
      const std::uint32_t v = 1u << 30;
      for (int byte = 0; byte < 4; ++byte) exr[at + 4 * std::size_t(k) + std::size_t(byte)] = char(v >> (8 * byte));
    }
    test::WriteText(dir / "far.exr", exr);
    ExpectErrorContaining([&] { ReadExr(dir / "far.exr"); }, {"far.exr", "starts at (0, 1073741824), more than 16777216"});
    Imf::Header h(Imath::Box2i({-3, 5}, {1, 7}), Imath::Box2i({-3, 5}, {1, 7}));
    for (const char* c : {"R", "G", "B"}) h.channels().insert(c, Imf::Channel(Imf::FLOAT));
    std::vector<float> px(3 * 5 * 3);
    for (std::size_t i = 0; i < px.size(); ++i) px[i] = float(i);
    Imf::FrameBuffer fb;
    for (int c = 0; c < 3; ++c)
      fb.insert(std::string(1, "RGB"[c]),
                Imf::Slice::Make(Imf::FLOAT, px.data() + c, h.dataWindow(), 3 * sizeof(float), 15 * sizeof(float)));
    {
      Imf::OutputFile out((dir / "offset.exr").c_str(), h);
      out.setFrameBuffer(fb);
      out.writePixels(3);
    }
    const RadianceImage back = ReadExr(dir / "offset.exr");
    ASSERT_EQ(back.width(), 5);
    ASSERT_EQ(back.height(), 3);
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 5; ++x) {
        const std::size_t i = 3 * (std::size_t(y) * 5 + std::size_t(x));
        EXPECT_EQ(back(x, y).x, px[i]);
        EXPECT_EQ(back(x, y).z, px[i + 2]);
      }
  }
  // A header with 300 float channels over a 60000-pixel-wide window (ZIP: 16 lines a chunk):
  // one chunk would decode to 1098 MiB, which OpenEXR allocates before reading (the fuzzer's
  // 1.3 KB input asked for 1.9 GB this way). Built byte by byte: only the header matters.
  {
    std::string h("\x76\x2f\x31\x01\x02\x00\x00\x00", 8);
    const auto u32 = [](std::uint32_t v) { return std::string{char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; };
    const auto attr = [&](const std::string& name, const std::string& type, const std::string& value) {
      h += name + '\0' + type + '\0' + u32(std::uint32_t(value.size())) + value;
    };
    std::string channels;
    for (int c = 0; c < 300; ++c) channels += "c" + std::to_string(c) + '\0' + u32(2) + std::string(4, '\0') + u32(1) + u32(1);
    channels += '\0';
    attr("channels", "chlist", channels);
    attr("compression", "compression", std::string(1, '\x03'));
    attr("dataWindow", "box2i", u32(0) + u32(0) + u32(59999) + u32(0));
    attr("displayWindow", "box2i", u32(0) + u32(0) + u32(59999) + u32(0));
    attr("lineOrder", "lineOrder", std::string(1, '\0'));
    h += '\0';
    h += std::string(64, '\0');  // the offset table and a little more
    test::WriteText(dir / "channels.exr", h);
    ExpectErrorContaining([&] { ReadExr(dir / "channels.exr"); },
                          {"channels.exr", "chunks of 1098 MiB (1200 bytes per pixel), more than the 256 MiB"});
    // A header naming its data window twice (a fuzzer input whose first window was 2^30 wide):
    // which one OpenEXR keeps is not guessed, the file is refused.
    const std::string window = std::string("dataWindow") + '\0' + "box2i" + '\0';
    std::string twice = test::ReadText(dir / "wide.exr");
    const std::size_t at = twice.find(window);
    twice.insert(at, twice.substr(at, window.size() + 4 + 16));
    test::WriteText(dir / "twice.exr", twice);
    ExpectErrorContaining([&] { ReadExr(dir / "twice.exr"); }, {"twice.exr", "names the attribute 'dataWindow' twice"});
  }
  // Not an OpenEXR file at all.
  test::WriteText(dir / "text.exr", "hello, this is text");
  ExpectErrorContaining([&] { ReadExr(dir / "text.exr"); }, {"text.exr", "no OpenEXR magic number"});
}

}  // namespace
}  // namespace hdrf::io
