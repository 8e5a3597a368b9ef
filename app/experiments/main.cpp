// hdrfusion-experiments: the paper's experiments and the figures of docs/results, apart from
// the product (not installed by the package). Every subcommand writes only under --out.
#include <memory>
#include <vector>

#include "cli/run_commands.h"
#include "experiments.h"

namespace {

using namespace hdrf::experiments;

// Options every tracking run shares (tracking, paper).
void AddTrackingOptions(CLI::App* cmd, TrackingExperimentArgs& t) {
  cmd->add_option("--frames", t.frames, "Frames of each sequence")->check(CLI::Range(5, 100000))
      ->capture_default_str();
  cmd->add_option("--size", t.size, "Image size, WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--ae", t.ae_modes, "Auto-exposure modes")->delimiter(',')
      ->check(CLI::IsMember({"flicker", "smooth", "fixed"}))->capture_default_str();
  cmd->add_option("--work", t.work,
                  "Keep the sequences every tracker reads in this folder (its room-* and peers-* folders are "
                  "replaced); default: a temporary folder, removed after");
  cmd->add_option("--peers", t.peers_program,
                  "The hdrfusion-peers program (OpenCV rgbd, Open3D) to run on the same sequences; without it "
                  "the peers are not run");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"HDRFusion experiments: the paper's tables and figures, regenerated", "hdrfusion-experiments"};
  app.require_subcommand(1);
  std::vector<Command> commands;

  auto out = std::make_shared<std::string>();
  auto pairs = std::make_shared<int>(10);
  auto* landscape = app.add_subcommand("landscape", "Error functions around the true pose (the paper's figure)");
  landscape->add_option("--out", *out, "Results folder")->required();
  landscape->add_option("--pairs", *pairs, "Frame pairs a stop or more apart")->check(CLI::Range(1, 50))
      ->capture_default_str();
  commands.push_back({landscape, [out, pairs] { return RunLandscape(*out, *pairs, 10); }});

  auto* nr = app.add_subcommand("nr-figure", "Normalized radiance across a strong exposure change");
  nr->add_option("--out", *out, "Results folder")->required();
  commands.push_back({nr, [out] { return RunNrFigure(*out); }});

  auto tracking_args = std::make_shared<TrackingExperimentArgs>();
  auto* tracking = app.add_subcommand("tracking", "Every tracker and the peers over the synthetic room");
  tracking->add_option("--out", tracking_args->out, "Results folder")->required();
  AddTrackingOptions(tracking, *tracking_args);
  commands.push_back({tracking, [tracking_args] { return RunTrackingExperiment(*tracking_args); }});

  auto real_args = std::make_shared<RealTrackingArgs>();
  auto* real = app.add_subcommand("real", "Our trackers and the peers on a real 7-Scenes recording");
  real->add_option("--data", real_args->data,
                   "7-Scenes folders (frames/, camera-intrinsics.txt); with several, each gets OUT/<folder name>/")
      ->required();
  real->add_option("--out", real_args->out, "Results folder")->required();
  real->add_option("--work", real_args->work, "Folder for the sequence every tracker reads (default: OUT/work)");
  real->add_option("--peers", real_args->peers_program, "The hdrfusion-peers program to run on the same frames");
  commands.push_back({real, [real_args] { return RunRealTracking(*real_args); }});

  auto radiance_frames = std::make_shared<int>(300);
  auto radiance_size = std::make_shared<std::string>("320x240");
  auto* radiance = app.add_subcommand("radiance", "Fused radiance against the truth; dynamic range");
  radiance->add_option("--out", *out, "Results folder")->required();
  radiance->add_option("--frames", *radiance_frames, "Frames per scene and mode")->check(CLI::Range(5, 100000))
      ->capture_default_str();
  radiance->add_option("--size", *radiance_size, "Image size, WIDTHxHEIGHT")->capture_default_str();
  commands.push_back({radiance, [out, radiance_frames, radiance_size] {
                        return RunRadianceAccuracy(*out, *radiance_frames, *radiance_size);
                      }});

  auto cal = std::make_shared<CalibrationBenchArgs>();
  auto* calibration = app.add_subcommand("calibration", "Response and noise recovery on every DoRF curve");
  calibration->add_option("--out", cal->out, "Results folder")->required();
  calibration->add_option("--data", cal->data, "Folder holding dorf/ and emor/")->required();
  calibration->add_option("--sweeps", cal->sweeps, "At most this many sweeps of 3 curves (default: all 67)")
      ->check(CLI::Range(1, 1000));
  calibration->add_option("--scene", cal->scene, "Scene of the simulated sweeps")
      ->check(CLI::IsMember({"room", "desk", "hall"}))->capture_default_str();
  calibration->add_option("--noise-scale", cal->noise_scale, "Multiplies the simulated sensor noise")
      ->check(CLI::Range(0.0, 10.0))->capture_default_str();
  commands.push_back({calibration, [cal] { return RunCalibrationAccuracy(*cal); }});

  auto paper_args = std::make_shared<TrackingExperimentArgs>();
  auto data = std::make_shared<std::string>();
  auto* paper = app.add_subcommand("paper", "All of the above, then the index README.md of --out");
  paper->add_option("--out", paper_args->out, "Results folder (docs/results to publish)")->required();
  paper->add_option("--data", *data, "Folder holding dorf/ and emor/ (without it: no calibration section)");
  paper->add_option("--pairs", *pairs, "Landscape: frame pairs")->check(CLI::Range(1, 50))->capture_default_str();
  AddTrackingOptions(paper, *paper_args);
  commands.push_back({paper, [paper_args, pairs, data] { return RunPaper(*paper_args, *pairs, *data); }});

  commands.push_back(AddContactSheetCommand(app));

  return hdrf::cli::Run(app, commands, argc, argv);
}
