// hdrfusion-experiments contact-sheet SEQUENCE --out sheet.png: colour | depth | HDR (tone-mapped) for a
// few frames of a sequence, side by side, with one tone-mapping scale for all rows so that
// constant radiance looks constant while the delivered colour flickers.
#include <algorithm>
#include <cstdio>

#include "experiments.h"
#include "common/error.h"
#include "io/image_io.h"
#include "io/sequence.h"
#include "tonemap/display.h"

namespace hdrf::experiments {

Command AddContactSheetCommand(CLI::App& app) {
  struct Args {
    std::string seq, out;
    int rows = 4;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("contact-sheet",
                                 "PNG of colour, depth and tone-mapped HDR for a few frames");
  cmd->add_option("SEQUENCE", a->seq, "Sequence folder")->required();
  cmd->add_option("--out", a->out, "Output PNG")->required();
  cmd->add_option("--rows", a->rows, "Frames shown, evenly spread")->check(CLI::Range(1, 16))
      ->capture_default_str();
  return {cmd, [a] {
    const io::SequenceReader seq(a->seq);
    if (!seq.has_hdr())
      std::fprintf(stderr, "contact-sheet: %s has no hdr/*.exr: the HDR column stays black\n",
                   a->seq.c_str());
    const int n = std::min<int>(a->rows, int(seq.size()));
    const int w = seq.sensor().camera.width, h = seq.sensor().camera.height, gap = 4;
    RadianceImage hdr_all(w, h * n);
    std::vector<io::Frame> frames;
    for (int r = 0; r < n; ++r) {
      const std::size_t i = n == 1 ? 0 : std::size_t(r) * (seq.size() - 1) / std::size_t(n - 1);
      frames.push_back(seq.ReadFrame(i));
      if (seq.has_hdr()) {
        const RadianceImage hdr = seq.ReadHdr(i);
        std::copy(hdr.data(), hdr.data() + hdr.size(), hdr_all.data() + std::size_t(r) * w * h);
      }
    }
    const ColorImage hdr_tm = tonemap::Reinhard(hdr_all);
    ColorImage sheet(3 * w + 2 * gap, n * h + (n - 1) * gap, Rgb8{255, 255, 255});
    for (int r = 0; r < n; ++r) {
      const ColorImage depth = frames[r].depth_m.empty()
                                   ? ColorImage(w, h)
                                   : tonemap::ColorizeDepth(frames[r].depth_m, 0.4f, 4.5f);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const int yy = r * (h + gap) + y;
          sheet(x, yy) = frames[r].color(x, y);
          sheet(w + gap + x, yy) = depth(x, y);
          sheet(2 * (w + gap) + x, yy) = hdr_tm(x, r * h + y);
        }
    }
    io::WriteColorPng(a->out, sheet);
    std::printf("wrote %s (%d frames: colour | depth 0.4-4.5 m | HDR radiance, Reinhard)\n",
                a->out.c_str(), n);
    return 0;
  }};
}

}  // namespace hdrf::experiments
