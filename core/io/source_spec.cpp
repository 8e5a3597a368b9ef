#include "io/source_spec.h"

#include <charconv>
#include <cstdio>
#include <stdexcept>
#include <sstream>

#include "common/error.h"
#include "io/sequence_source.h"

namespace hdrf::io {

void ParseSize(const std::string& s, int* w, int* h) {
  char extra = 0;  // (320x240junk was taken as 320x240)
  if (std::sscanf(s.c_str(), "%dx%d%c", w, h, &extra) != 2 || *w <= 0 || *h <= 0)
    throw SettingError("--size", "expected WIDTHxHEIGHT such as 320x240, got '" + s + "'");
}

namespace {
// The whole of `v` as a number of type T: "12abc", "-1" for an unsigned seed, "" refused.
template <typename T>
T Whole(const std::string& v) {
  T x{};
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
  if (ec != std::errc() || end != v.data() + v.size() || v.empty()) throw std::invalid_argument(v);
  return x;
}
}  // namespace

std::vector<std::pair<std::string, std::string>> SplitSpec(const std::string& spec, std::size_t from,
                                                           const std::string& example) {
  std::vector<std::pair<std::string, std::string>> out;
  if (from >= spec.size()) return out;
  std::stringstream ss(spec.substr(from));
  std::string kv;
  while (std::getline(ss, kv, ',')) {
    if (kv.empty()) continue;
    const auto eq = kv.find('=');
    if (eq == std::string::npos)
      throw SettingError("SOURCE", "'" + kv + "' in '" + spec + "' is not key=value (" +
                                       (example.empty() ? std::string("key=value pairs, separated by commas")
                                                        : "e.g. " + example) +
                                       ")");
    out.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
  }
  return out;
}

std::unique_ptr<pipeline::FrameSource> OpenSource(const std::string& spec, const std::string& response) {
  const std::string prefix = "synthetic:";
  if (spec.rfind(prefix, 0) == 0) {
    sim::SimOptions o;
    for (const auto& [k, v] : SplitSpec(spec, prefix.size(), "synthetic:size=320x240,frames=300")) {
      try {
        if (k == "scene") o.scene = v;
        else if (k == "seed") o.seed = Whole<std::uint32_t>(v);
        else if (k == "frames") o.frames = Whole<int>(v);
        else if (k == "ae") o.ae.mode = sim::ParseAeMode(v);
        else if (k == "exposure") o.ae.fixed_ms = Whole<double>(v);
        else if (k == "size") ParseSize(v, &o.width, &o.height);
        else throw SettingError("SOURCE", "unknown synthetic setting '" + k +
                                              "' (scene, seed, frames, ae, exposure, size)");
      } catch (const std::logic_error&) {
        throw SettingError("SOURCE", "cannot parse '" + k + "=" + v + "' in '" + spec + "'");
      }
    }
    return std::make_unique<pipeline::SyntheticFrameSource>(o);
  }
  auto seq = std::make_unique<SequenceFrameSource>(spec);
  if (!seq->sensor().response) {
    if (response == "srgb") {
      seq->AssumeSrgbResponse();
    } else {
      throw InputError(std::filesystem::path(spec) / "sensor.json",
                       "has no 'response' calibration: HDR radiance needs the camera response. "
                       "Calibrate the camera (hdrfusion calibrate) or pass --response srgb to assume "
                       "an sRGB camera");
    }
  }
  return seq;
}

}  // namespace hdrf::io
