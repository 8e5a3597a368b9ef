// Subcommands of the `hdrfusion` tool. Each registers its options on the parent app.
#pragma once

#include "cli/run_commands.h"

namespace hdrf::cli {

Command AddInfoCommand(CLI::App& app);
Command AddRadianceCommand(CLI::App& app);
Command AddSimulateCommand(CLI::App& app);
Command AddBenchCommand(CLI::App& app);
Command AddCalibrateCommand(CLI::App& app);
Command AddMergeCommand(CLI::App& app);
Command AddScanCommand(CLI::App& app);
Command AddEvalCommand(CLI::App& app);
Command AddSensorsCommand(CLI::App& app);
Command AddRecordCommand(CLI::App& app);
Command AddCaptureSweepCommand(CLI::App& app);
Command AddTonemapCommand(CLI::App& app);
Command AddExportCommand(CLI::App& app);
Command AddSettingsCommand(CLI::App& app);

}  // namespace hdrf::cli
