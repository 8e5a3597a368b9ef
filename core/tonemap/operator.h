// Tone-mapping operators, each declared with its parameters (key, range, default, unit,
// help) so that the CLI's `--set key=value`, the studio's panel and the docs are all
// generated from one declaration.
//
// Every operator maps linear scene radiance to *display-linear* RGB in [0, 1]: the fraction
// of the display's range each channel should emit. The last step, the display encoding, is
// not the operator's: the studio and the CLI apply the OpenColorIO display/view transform
// (io/ocio_display.h), and comparisons with reference programs apply the display model's
// own gamma (EncodeGamma).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/cuda_runtime.h"
#include "common/image.h"

namespace hdrf::tonemap {

struct ParamDecl {
  enum class Kind { kReal, kInt, kBool };
  std::string key;    // as written on the command line: --set key=value
  std::string label;  // short, for forms
  Kind kind = Kind::kReal;
  double min = 0, max = 1, def = 0;
  std::string unit;  // "" where the value has none
  std::string help;  // one sentence
};

// Named values for a subset of the parameters (display presets).
struct Preset {
  std::string key, label;
  std::map<std::string, double> values;
};

using Params = std::map<std::string, double>;

class Operator;

struct OperatorDecl {
  std::string key;    // "mantiuk08"
  std::string label;  // "Mantiuk 2008 (display adaptive)"
  std::string help;
  std::vector<ParamDecl> params;
  std::vector<Preset> presets;
  bool local = false;  // a local operator (its result depends on neighbours, not only the pixel)
  // Makes an instance on a device (kCuda: throws hdrf::Error where the build or the machine
  // has no usable GPU; the per-pixel operators run on the CPU either way).
  std::function<std::unique_ptr<Operator>(const Params&, Device)> make;
};

// Timing of a frame for the temporal filters: seconds since any fixed origin, or a
// negative value for a still image (no temporal filtering; the filter state is reset).
struct FrameTime {
  double seconds = -1;
  static FrameTime Still() { return {}; }
};

// One operator instance per view: it holds the state of its temporal filter (if any).
class Operator {
 public:
  virtual ~Operator() = default;
  // `out` receives display-linear RGB in [0, 1]; pixels of `in` that are all zero (no data)
  // stay black and are left out of any image statistics; non-finite values count as no
  // data.
  virtual void Map(const RadianceImage& in, Image<Float3>& out, FrameTime t) = 0;
  // The same mapping for a list of colours (mesh vertices). A global operator applies the
  // curve of the last image it mapped (mantiuk08: without its brightness hold, which steadies
  // a view whose content changes, not a whole model); with none yet, the list is mapped on
  // its own.
  virtual std::vector<Float3> MapList(const std::vector<Float3>& in);
  // The tone curve of the last Map, where the operator has one: log10 input luminance
  // against display-linear luminance. Empty otherwise.
  struct Curve {
    std::vector<double> log_lum, display;
  };
  virtual Curve LastCurve() const { return {}; }

 protected:
  // Global part learnt from the last image (log10 luminance -> display-linear luminance),
  // used by MapList; operators with a curve fill it from their curve.
  Curve learnt_;
  void LearnCurve(const RadianceImage& in, const Image<Float3>& out);
};

// All operators, in the order the studio lists them (the first is the default).
const std::vector<OperatorDecl>& Operators();
// The operator with `key`; throws SettingError naming `setting` (the flag it came from)
// and listing the known keys.
const OperatorDecl& FindOperator(const std::string& key, const std::string& setting = "--op");

// The declared defaults, overridden by `values` (checked: unknown keys and values out of
// range throw SettingError naming the key, its range and unit). A key "preset" is not a
// parameter: use ApplyPreset.
Params ResolveParams(const OperatorDecl& op, const Params& values);
// `values` with the preset's entries set (throws SettingError listing the presets).
Params ApplyPreset(const OperatorDecl& op, const std::string& preset, Params values);
// Parses "key=value" (value a number, or on/off/true/false for booleans) into `values`.
void ParseSetting(const OperatorDecl& op, const std::string& text, Params& values);

// "OP[,key=value...]" (the CLI's --tone and the studio's): the operator (checked) and its
// values (checked against the declaration); and back.
struct Spec {
  std::string op;
  Params values;
};
Spec ParseSpec(const std::string& text, const std::string& setting = "--tone");
std::string FormatSpec(const Spec& spec);

// Display-linear to display code values with a power-law display (gamma), in place.
void EncodeGamma(Image<Float3>& img, double gamma);

}  // namespace hdrf::tonemap
