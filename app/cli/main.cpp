// hdrfusion: the command-line face of HDRFusion Studio. Everything the studio does can be
// done here, headless.
#include <vector>

#include "cli/commands.h"
#include "cli/run_commands.h"

int main(int argc, char** argv) {
  CLI::App app{"HDRFusion: HDR RGB-D scanning for auto-exposure cameras", "hdrfusion"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "hdrfusion 0.1.0");
  app.footer("Each command's options: hdrfusion COMMAND --help. Manual: man hdrfusion. Documentation (the\n"
             "docs/ named in the help): docs/index.md in the source, /usr/share/doc/hdrfusion-studio/ when installed.");
  const std::vector<hdrf::cli::Command> commands = {
      hdrf::cli::AddInfoCommand(app),
      hdrf::cli::AddRadianceCommand(app),
      hdrf::cli::AddSimulateCommand(app),
      hdrf::cli::AddScanCommand(app),
      hdrf::cli::AddEvalCommand(app),
      hdrf::cli::AddCalibrateCommand(app),
      hdrf::cli::AddMergeCommand(app),
      hdrf::cli::AddSensorsCommand(app),
      hdrf::cli::AddRecordCommand(app),
      hdrf::cli::AddCaptureSweepCommand(app),
      hdrf::cli::AddTonemapCommand(app),
      hdrf::cli::AddExportCommand(app),
      hdrf::cli::AddSettingsCommand(app),
      hdrf::cli::AddBenchCommand(app),
  };
  return hdrf::cli::Run(app, commands, argc, argv);
}
