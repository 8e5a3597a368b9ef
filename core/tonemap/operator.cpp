#include "tonemap/operator.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/error.h"
#include "tonemap/exposure/exposure.h"
#include "tonemap/linear/linear.h"
#include "tonemap/mantiuk06/mantiuk06.h"
#include "tonemap/mantiuk08/mantiuk08.h"
#include "tonemap/reinhard/reinhard.h"

namespace hdrf::tonemap {

namespace {
constexpr double kLearnMin = -8, kLearnStep = 0.1;
constexpr int kLearnBins = 161;

bool NoData(Float3 c) {
  return !(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) || (c.x == 0 && c.y == 0 && c.z == 0);
}

std::string FormatNumber(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}
}  // namespace

void Operator::LearnCurve(const RadianceImage& in, const Image<Float3>& out) {
  std::vector<double> sum(kLearnBins, 0.0), n(kLearnBins, 0.0);
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (NoData(in[i])) continue;
    const double l = Luminance(in[i]), d = Luminance(out[i]);
    if (!(l > 0) || !(d > 0)) continue;
    const int b = std::clamp(int(std::lround((std::log10(l) - kLearnMin) / kLearnStep)), 0, kLearnBins - 1);
    sum[std::size_t(b)] += std::log10(d);
    n[std::size_t(b)] += 1;
  }
  learnt_ = {};
  int first = -1, last = -1;
  for (int b = 0; b < kLearnBins; ++b)
    if (n[std::size_t(b)] > 0) {
      if (first < 0) first = b;
      last = b;
    }
  if (first < 0) return;
  // Mean display log luminance per input bin; empty bins interpolated; kept non-decreasing.
  double prev = -1e30;
  for (int b = 0; b < kLearnBins; ++b) {
    double v;
    if (b <= first) {
      v = sum[std::size_t(first)] / n[std::size_t(first)];
    } else if (b >= last) {
      v = sum[std::size_t(last)] / n[std::size_t(last)];
    } else if (n[std::size_t(b)] > 0) {
      v = sum[std::size_t(b)] / n[std::size_t(b)];
    } else {
      int nx = b + 1;
      while (n[std::size_t(nx)] == 0) ++nx;
      const double right = sum[std::size_t(nx)] / n[std::size_t(nx)];
      v = prev + (right - prev) / double(nx - b + 1);
    }
    v = std::max(v, prev);
    prev = v;
    learnt_.log_lum.push_back(kLearnMin + kLearnStep * b);
    learnt_.display.push_back(std::pow(10.0, v));
  }
}

std::vector<Float3> Operator::MapList(const std::vector<Float3>& in) {
  std::vector<Float3> out(in.size(), Float3{0, 0, 0});
  if (in.empty()) return out;
  if (learnt_.log_lum.empty()) {
    // No image seen yet: map the list on its own, laid out as a near-square image.
    const int w = std::max(1, int(std::ceil(std::sqrt(double(in.size())))));
    const int h = int((in.size() + std::size_t(w) - 1) / std::size_t(w));
    RadianceImage img(w, h, Float3{0, 0, 0});
    std::copy(in.begin(), in.end(), img.data());
    Image<Float3> mapped(w, h);
    const Curve keep = learnt_;
    Map(img, mapped, FrameTime::Still());
    learnt_ = keep;
    std::copy(mapped.data(), mapped.data() + in.size(), out.begin());
    return out;
  }
  const auto& xs = learnt_.log_lum;
  const auto& ys = learnt_.display;
  const double x0 = xs.front(), dx = xs.size() > 1 ? xs[1] - xs[0] : 1.0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (NoData(in[i])) continue;
    const Float3 c{std::max(0.f, in[i].x), std::max(0.f, in[i].y), std::max(0.f, in[i].z)};
    const double l = Luminance(c);
    if (!(l > 0)) continue;
    const double f = std::clamp((std::log10(l) - x0) / dx, 0.0, double(xs.size() - 1));
    const std::size_t k = std::min(std::size_t(f), xs.size() - 2);
    const double d = ys[k] + (ys[k + 1] - ys[k]) * (f - double(k));
    const float s = float(d / l);
    out[i] = {std::min(1.f, c.x * s), std::min(1.f, c.y * s), std::min(1.f, c.z * s)};
  }
  return out;
}

const std::vector<OperatorDecl>& Operators() {
  static const std::vector<OperatorDecl> ops = {m08::Declaration(), m06::Declaration(), reinhard::Declaration(),
                                                exposure::Declaration(), linear::Declaration()};
  return ops;
}

const OperatorDecl& FindOperator(const std::string& key, const std::string& setting) {
  std::string known;
  for (const auto& op : Operators()) {
    if (op.key == key) return op;
    known += (known.empty() ? "" : ", ") + op.key;
  }
  throw SettingError(setting, "unknown tone-mapping operator '" + key + "' (known: " + known + ")");
}

Params ResolveParams(const OperatorDecl& op, const Params& values) {
  Params out;
  for (const auto& p : op.params) out[p.key] = p.def;
  for (const auto& entry : values) {
    const std::string& key = entry.first;  // a plain reference: lambdas may capture it in every compiler
    const double v = entry.second;
    auto it = std::find_if(op.params.begin(), op.params.end(), [&](const ParamDecl& p) { return p.key == key; });
    if (it == op.params.end()) {
      std::string known;
      for (const auto& p : op.params) known += (known.empty() ? "" : ", ") + p.key;
      throw SettingError(key, "not a parameter of " + op.key + " (its parameters: " + known + ")");
    }
    if (!(v >= it->min && v <= it->max))
      throw SettingError(key, FormatNumber(v) + " is outside [" + FormatNumber(it->min) + ", " + FormatNumber(it->max) +
                                  "]" + (it->unit.empty() ? "" : " " + it->unit));
    if (it->kind != ParamDecl::Kind::kReal && v != std::round(v))
      throw SettingError(key, "expects " + std::string(it->kind == ParamDecl::Kind::kBool ? "on or off" : "a whole number"));
    out[key] = v;
  }
  return out;
}

Params ApplyPreset(const OperatorDecl& op, const std::string& preset, Params values) {
  std::string known;
  for (const auto& p : op.presets) {
    if (p.key == preset) {
      for (const auto& [k, v] : p.values) values[k] = v;
      return values;
    }
    known += (known.empty() ? "" : ", ") + p.key;
  }
  throw SettingError("preset", "unknown preset '" + preset + "' for " + op.key +
                                   (known.empty() ? " (it has none)" : " (known: " + known + ")"));
}

void ParseSetting(const OperatorDecl& op, const std::string& text, Params& values) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw SettingError("--set", "'" + text + "' is not key=value");
  const std::string key = text.substr(0, eq), value = text.substr(eq + 1);
  if (key == "preset") {
    values = ApplyPreset(op, value, values);
    return;
  }
  if (value == "on" || value == "true" || value == "yes") {
    values[key] = 1;
    return;
  }
  if (value == "off" || value == "false" || value == "no") {
    values[key] = 0;
    return;
  }
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != value.size() || !std::isfinite(v))
    throw SettingError(key, "'" + value + "' is not a number");
  values[key] = v;
}

Spec ParseSpec(const std::string& text, const std::string& setting) {
  Spec s;
  s.op = text.substr(0, text.find(','));
  const OperatorDecl& d = FindOperator(s.op, setting);
  for (std::size_t at = text.find(','); at != std::string::npos;) {
    const std::size_t next = text.find(',', at + 1);
    ParseSetting(d, text.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1), s.values);
    at = next;
  }
  ResolveParams(d, s.values);  // checks
  return s;
}

std::string FormatSpec(const Spec& spec) {
  std::string out = spec.op;
  for (const auto& [k, v] : spec.values) out += "," + k + "=" + FormatNumber(v);
  return out;
}

void EncodeGamma(Image<Float3>& img, double gamma) {
  const float inv = float(1 / gamma);
  for (std::size_t i = 0; i < img.size(); ++i) {
    Float3& c = img[i];
    c = {std::pow(std::clamp(c.x, 0.f, 1.f), inv), std::pow(std::clamp(c.y, 0.f, 1.f), inv),
         std::pow(std::clamp(c.z, 0.f, 1.f), inv)};
  }
}

}  // namespace hdrf::tonemap
