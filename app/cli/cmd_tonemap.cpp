// hdrfusion tonemap IN.exr --op OPERATOR [--set key=value ...] --out OUT.png|OUT.exr
// Tone-maps one HDR image with any declared operator; parameters by key (see --list).
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "common/error.h"
#include "io/exr.h"
#include "io/image_io.h"
#include "io/ocio_display.h"
#include "io/output_file.h"
#include "tonemap/operator.h"

namespace hdrf::cli {

namespace {

void ListOperators() {
  for (const auto& op : tonemap::Operators()) {
    std::printf("%s: %s\n  %s\n", op.key.c_str(), op.label.c_str(), op.help.c_str());
    for (const auto& p : op.params) {
      const bool flag = p.kind == tonemap::ParamDecl::Kind::kBool;
      if (flag)
        std::printf("    %-18s %s (default %s). %s\n", p.key.c_str(), "on|off", p.def != 0 ? "on" : "off", p.help.c_str());
      else
        std::printf("    %-18s [%g, %g]%s%s (default %g). %s\n", p.key.c_str(), p.min, p.max, p.unit.empty() ? "" : " ",
                    p.unit.c_str(), p.def, p.help.c_str());
    }
    for (const auto& pr : op.presets) {
      std::string v;
      for (const auto& [k, x] : pr.values) {
        char buf[64];
        std::snprintf(buf, sizeof buf, " %s=%g", k.c_str(), x);
        v += buf;
      }
      std::printf("    preset=%-11s %s:%s\n", pr.key.c_str(), pr.label.c_str(), v.c_str());
    }
  }
}

}  // namespace

Command AddTonemapCommand(CLI::App& app) {
  struct Args {
    std::string in, out, op = "mantiuk08", curve, encode = "ocio", ocio_config, display, view, device = "cpu";
    std::vector<std::string> sets;
    bool list = false;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("tonemap", "Tone-map an HDR image (OpenEXR) for display with a declared operator");
  cmd->add_option("IN", a->in, "Input OpenEXR image (linear RGB)");
  cmd->add_option("--op", a->op, "Operator: mantiuk08, mantiuk06, reinhard, exposure, linear (see --list)");
  cmd->add_option("--set", a->sets, "Parameter as key=value (repeatable; preset=NAME applies a display preset)");
  cmd->add_option("--out", a->out, "Output: .png (display-encoded, 8 bit) or .exr (display-linear floats)");
  cmd->add_option("--curve", a->curve, "Also write the tone curve (CSV: log10 luminance, display-linear luminance)");
  cmd->add_option("--encode", a->encode, "Display encoding of a PNG: 'ocio' (the display/view transform) or 'gamma' "
                                         "(the operator's display gamma, 2.2 where it has none)")
      ->check(CLI::IsMember({"ocio", "gamma"}));
  cmd->add_option("--ocio-config", a->ocio_config, "OpenColorIO config file (default: the built-in sRGB config)");
  cmd->add_option("--display", a->display, "OpenColorIO display (default: the config's; the built-in one has sRGB)");
  cmd->add_option("--view", a->view, "OpenColorIO view (default: the display's; the built-in sRGB has Standard and Raw)");
  cmd->add_option("--device", a->device, "cpu or cuda (the Mantiuk operators run on the GPU)")
      ->check(CLI::IsMember({"cpu", "cuda"}));
  cmd->add_flag("--list", a->list, "List the operators and their parameters, then exit");
  return {cmd, [a] {
    if (a->list) {
      ListOperators();
      return 0;
    }
    if (a->in.empty()) throw SettingError("IN", "an input OpenEXR image is required (or --list)");
    if (a->out.empty()) throw SettingError("--out", "an output file (.png or .exr) is required");
    const std::filesystem::path out(a->out);
    const std::string ext = out.extension().string();
    if (ext != ".png" && ext != ".exr") throw SettingError("--out", a->out + ": the output must end in .png or .exr");
    io::CheckOutputFile(out, {a->in});
    const tonemap::OperatorDecl& decl = tonemap::FindOperator(a->op);
    tonemap::Params values;
    for (const auto& s : a->sets) tonemap::ParseSetting(decl, s, values);
    const tonemap::Params params = tonemap::ResolveParams(decl, values);
    std::unique_ptr<io::OcioDisplay> ocio;
    if (ext == ".png" && a->encode == "ocio")
      ocio = a->ocio_config.empty() ? std::make_unique<io::OcioDisplay>(a->display, a->view)
                                    : std::make_unique<io::OcioDisplay>(a->ocio_config, a->display, a->view);
    const RadianceImage hdr = io::ReadExr(a->in);
    Device device = a->device == "cuda" ? Device::kCuda : Device::kCpu;
    std::string why;
    if (device == Device::kCuda && !CudaAvailable(&why)) {
      std::fprintf(stderr, "hdrfusion: CUDA not usable (%s); running on the CPU\n", why.c_str());
      device = Device::kCpu;
    }
    auto op = decl.make(params, device);
    Image<Float3> mapped;
    const auto t0 = std::chrono::steady_clock::now();
    op->Map(hdr, mapped, tonemap::FrameTime::Still());
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!a->curve.empty()) {
      const auto c = op->LastCurve();
      if (c.log_lum.empty())
        throw SettingError("--curve", a->op + " is a local operator and has no single tone curve");
      std::string text = "# " + decl.key + " tone curve of " + a->in + "\n# log10_luminance display_linear\n";
      for (std::size_t i = 0; i < c.log_lum.size(); ++i) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.2f %.6g\n", c.log_lum[i], c.display[i]);
        text += buf;
      }
      io::WriteFileAtomically(a->curve, text);
    }
    if (ext == ".exr") {
      io::WriteExr(out, mapped, io::ExrPrecision::kFloat);
    } else {
      if (ocio) {
        ocio->Apply(mapped);
      } else {
        tonemap::EncodeGamma(mapped, params.count("gamma") && a->op == "mantiuk08" ? params.at("gamma") : 2.2);
      }
      io::WriteColorPng(out, io::OcioDisplay::Quantise(mapped));
    }
    const std::string how = ext == ".exr" ? "display-linear" : ocio ? "OpenColorIO " + ocio->display() + " / " + ocio->view() : "gamma";
    std::printf("%s: %s on %dx%d in %.1f ms (%s); wrote %s (%s)\n", a->in.c_str(), decl.key.c_str(), hdr.width(),
                hdr.height(), ms, DeviceName(device), a->out.c_str(), how.c_str());
    return 0;
  }};
}

}  // namespace hdrf::cli
