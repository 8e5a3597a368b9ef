// hdrfusion simulate: writes a synthetic auto-exposure RGB-D sequence with full ground truth.
#include <chrono>
#include <cstdio>
#include <sstream>
#include <unistd.h>

#include "io/output_file.h"
#include "cli/commands.h"
#include "io/source_spec.h"
#include "cli/progress.h"
#include "common/error.h"
#include "io/sensor_json.h"
#include "io/sequence.h"
#include "sim/synthetic_source.h"

namespace hdrf::cli {

namespace {
// Exposure times a camera can have: a microsecond to 100 seconds.
constexpr double kMinExposureMs = 0.001, kMaxExposureMs = 100000;

std::vector<double> ParseList(const std::string& s, const char* flag) {
  std::vector<double> out;
  std::stringstream ss(s);
  std::string tok;
  while (std::getline(ss, tok, ',')) {
    try {
      std::size_t used = 0;
      out.push_back(std::stod(tok, &used));
      if (used != tok.size()) throw std::invalid_argument(tok);
    } catch (const std::exception&) {
      throw SettingError(flag, "cannot parse '" + tok + "' as a number of milliseconds");
    }
    if (!(out.back() >= kMinExposureMs && out.back() <= kMaxExposureMs))
      throw SettingError(flag, "'" + tok + "' ms is not an exposure time (" + std::to_string(kMinExposureMs) +
                                   " to " + std::to_string(int(kMaxExposureMs)) + " ms)");
  }
  return out;
}
}  // namespace

Command AddSimulateCommand(CLI::App& app) {
  struct Args {
    std::string out, scene = "room", size = "320x240", ae = "smooth", exposures, sweep_exposures,
                response;
    std::uint32_t seed = 1;
    int frames = 300, sweep_repeats = 5;
    double exposure_ms = 10;
    bool sweep = false, exact_depth = false;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand(
      "simulate", "Write a synthetic auto-exposure RGB-D sequence with ground truth");
  cmd->add_option("--out", a->out, "Output sequence folder (must be new or empty)")->required();
  cmd->add_option("--scene", a->scene, "Built-in scene")->check(CLI::IsMember({"room", "desk", "hall"}))
      ->capture_default_str();
  cmd->add_option("--seed", a->seed, "Seed: textures, lights, path, noise")->capture_default_str();
  cmd->add_option("--frames", a->frames, "Number of frames")->check(CLI::Range(1, 1000000))->capture_default_str();
  cmd->add_option("--size", a->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--ae", a->ae, "Auto exposure: fixed, smooth, flicker or list")
      ->check(CLI::IsMember({"fixed", "smooth", "flicker", "list"}))->capture_default_str();
  cmd->add_option("--exposure", a->exposure_ms, "Exposure (ms) for --ae fixed")
      ->check(CLI::Range(kMinExposureMs, kMaxExposureMs))->capture_default_str();
  cmd->add_option("--exposures", a->exposures, "Comma-separated exposures (ms) for --ae list");
  cmd->add_flag("--sweep", a->sweep, "Exposure sweep for calibration: static camera, "
                                     "each exposure --sweep-repeats times");
  cmd->add_option("--sweep-exposures", a->sweep_exposures,
                  "Comma-separated sweep exposures (ms); default half-stops 0.25..128");
  cmd->add_option("--sweep-repeats", a->sweep_repeats, "Frames per sweep exposure")
      ->check(CLI::Range(1, 10000))->capture_default_str();
  cmd->add_option("--response", a->response,
                  "sensor.json whose response and noise the simulated camera uses "
                  "(default: the built-in Xtion profile)");
  cmd->add_flag("--exact-depth", a->exact_depth, "No depth noise or dropouts");
  return {cmd, [a] {
    sim::SimOptions o;
    o.scene = a->scene;
    o.seed = a->seed;
    o.frames = a->frames;
    io::ParseSize(a->size, &o.width, &o.height);
    o.ae.mode = sim::ParseAeMode(a->ae);
    o.ae.fixed_ms = a->exposure_ms;
    if (!a->exposures.empty()) o.ae.list_ms = ParseList(a->exposures, "--exposures");
    o.sweep = a->sweep;
    o.sweep_repeats = a->sweep_repeats;
    if (!a->sweep_exposures.empty())
      o.sweep_exposures_ms = ParseList(a->sweep_exposures, "--sweep-exposures");
    if (!a->response.empty()) {
      const SensorInfo s = io::ReadSensorJson(a->response);
      if (!s.response || !s.noise)
        throw InputError(a->response, "needs both 'response' and 'noise' to drive the simulation");
      o.response = *s.response;
      o.noise = *s.noise;
    }
    o.depth.enabled = !a->exact_depth;
    io::CheckOutputFolderEarly(a->out, {a->response});
    sim::SyntheticSource source(o);
    io::SequenceWriter writer(a->out, source.sensor(), {.write_hdr = true});
    Progress progress("simulate", source.size());
    while (!source.done()) {
      const sim::SimFrame f = source.Next();
      writer.Add(f.timestamp, f.color, &f.depth, f.exposure_ms, f.T_world_camera, &f.radiance);
      progress.Step();
    }
    progress.Done();
    std::printf("wrote %d frames of scene '%s' (%dx%d, %s) to %s\n", source.size(),
                o.scene.c_str(), o.width, o.height,
                o.sweep ? "exposure sweep" : sim::AeModeName(o.ae.mode), a->out.c_str());
    return 0;
  }};
}

}  // namespace hdrf::cli
