// Subcommands of the `hdrfusion` tool. Each registers its options on the parent app.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace hdrf::cli {

struct Command {
  CLI::App* app;            // the subcommand, to ask whether it was chosen
  std::function<int()> run;  // runs it; returns the exit status
};

// "WIDTHxHEIGHT" (e.g. 320x240); throws SettingError naming --size otherwise.

Command AddInfoCommand(CLI::App& app);
Command AddRadianceCommand(CLI::App& app);
Command AddSimulateCommand(CLI::App& app);
Command AddContactSheetCommand(CLI::App& app);
Command AddBenchCommand(CLI::App& app);
Command AddCalibrateCommand(CLI::App& app);
Command AddMergeCommand(CLI::App& app);
Command AddScanCommand(CLI::App& app);
Command AddEvalCommand(CLI::App& app);

// The error-landscape figure (cmd_landscape.cpp), run by `bench --suite landscape`.
int RunLandscape(const std::string& out_dir, int pairs, int steps);
// The tracking experiment (cmd_tracking.cpp), run by `bench --suite tracking`.
struct TrackingExperimentArgs {
  int frames = 1000;
  std::string size = "320x240";
  std::vector<std::string> ae_modes = {"flicker", "smooth"};
  std::string out = "docs/results";
  std::string work = "build/bench-data";  // sequences written for the peers
  bool peers = true;
};
int RunTrackingExperiment(const TrackingExperimentArgs& a);
// Everything above, then docs/results/README.md (cmd_paper.cpp), `bench --suite paper`.
int RunPaper(const TrackingExperimentArgs& a, int pairs, const std::string& data_dir);
// Radiance accuracy and dynamic range per scene (cmd_radiance_bench.cpp), `bench --suite radiance`.
int RunRadianceAccuracy(const std::string& out_dir, int frames, const std::string& size);
// Response recovery on every DoRF curve (cmd_calibration_bench.cpp), `bench --suite
// calibration`: one sweep per 3 curves.
struct CalibrationBenchArgs {
  std::string out = "docs/results", data = "../shared/data", scene = "room";
  int sweeps = 0;            // > 0: at most this many sweeps
  double noise_scale = 1.0;  // multiplies the sensor noise (sigma_s, sigma_c)
};
int RunCalibrationAccuracy(const CalibrationBenchArgs& a);
// The normalized-radiance figure (cmd_nr_figure.cpp), run by `bench --suite nr-figure`.
int RunNrFigure(const std::string& out_dir);

}  // namespace hdrf::cli
