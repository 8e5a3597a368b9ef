// hdrfusion: the command-line face of HDRFusion Studio. Everything the studio does can be
// done here, headless.
#include <cstdio>
#include <exception>
#include <vector>

#include "cli/commands.h"
#include "common/error.h"

int main(int argc, char** argv) {
  CLI::App app{"HDRFusion: HDR RGB-D scanning for auto-exposure cameras", "hdrfusion"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "hdrfusion 0.1.0");
  const std::vector<hdrf::cli::Command> commands = {
      hdrf::cli::AddInfoCommand(app),
      hdrf::cli::AddRadianceCommand(app),
      hdrf::cli::AddSimulateCommand(app),
      hdrf::cli::AddScanCommand(app),
      hdrf::cli::AddEvalCommand(app),
      hdrf::cli::AddCalibrateCommand(app),
      hdrf::cli::AddMergeCommand(app),
      hdrf::cli::AddBenchCommand(app),
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    for (const auto& c : commands)
      if (c.app->parsed()) return c.run();
  } catch (const hdrf::Error& e) {
    std::fprintf(stderr, "hdrfusion: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hdrfusion: unexpected error: %s\n", e.what());
    return 2;
  }
  return 0;
}
