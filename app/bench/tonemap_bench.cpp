#include "tonemap_bench.h"

#include <algorithm>
#include <chrono>

#include "sim/synthetic_source.h"
#include "tonemap/mantiuk06/mantiuk06.h"
#include "tonemap/operator.h"

namespace hdrf::bench {

RadianceImage Resample(const RadianceImage& in, int w, int h) {
  RadianceImage out(w, h);
  const double sx = double(in.width()) / w, sy = double(in.height()) / h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Float3 s{0, 0, 0};
      int n = 0;
      for (int j = int(y * sy); j < std::min(in.height(), int((y + 1) * sy + 0.999)); ++j)
        for (int i = int(x * sx); i < std::min(in.width(), int((x + 1) * sx + 0.999)); ++i) s += in(i, j), ++n;
      out(x, y) = n ? s / float(n) : Float3{0, 0, 0};
    }
  return out;
}

std::vector<std::pair<std::string, RadianceImage>> SyntheticHdrFrames() {
  std::vector<std::pair<std::string, RadianceImage>> out;
  for (const char* scene : {"room", "desk"}) {
    sim::SimOptions o;
    o.scene = scene;
    o.width = 640, o.height = 480;
    o.frames = 1;
    sim::SyntheticSource src(o);
    out.emplace_back(std::string("synthetic ") + scene, src.Next().radiance);
  }
  return out;
}

std::vector<TonemapRow> RunTonemapBench(const std::vector<std::pair<std::string, const RadianceImage*>>& images,
                                        int frames, const std::vector<Device>& devices) {
  std::vector<TonemapRow> rows;
  for (const auto& [name, img] : images)
    for (const std::string op : {"mantiuk08", "mantiuk06", "reinhard"})
      for (const Device dev : devices) {
        if (dev == Device::kCuda && op == "reinhard") continue;
        const auto& decl = tonemap::FindOperator(op);
        const tonemap::Params p = tonemap::ResolveParams(decl, {});
        auto o = decl.make(p, dev);
        Image<Float3> out;
        o->Map(*img, out, tonemap::FrameTime::Still());
        const int n = op == "mantiuk06" && dev == Device::kCpu ? std::max(1, frames / 10) : frames;
        const auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < n; ++i) o->Map(*img, out, tonemap::FrameTime::Still());
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / n;
        TonemapRow r{name, op, dev, ms, 0};
        if (op == "mantiuk06") {
          Image<Float3> tmp;
          const auto opts = tonemap::m06::OptionsFrom(p);
          r.iterations = (dev == Device::kCuda ? tonemap::m06::MapCuda(*img, tmp, opts) : tonemap::m06::Map(*img, tmp, opts)).iterations;
        }
        rows.push_back(r);
      }
  return rows;
}

}  // namespace hdrf::bench
