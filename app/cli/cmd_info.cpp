// hdrfusion info SEQUENCE: what a recorded sequence holds.
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "io/sequence.h"
#include "io/sequence_summary.h"

namespace hdrf::cli {

Command AddInfoCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Describe a recorded sequence (layout: docs/formats.md)");
  auto folder = std::make_shared<std::string>();
  auto samples = std::make_shared<std::size_t>(30);
  cmd->add_option("SEQUENCE", *folder, "Sequence folder")->required();
  cmd->add_option("--depth-samples", *samples, "Depth frames read for the coverage figure")
      ->check(CLI::PositiveNumber);
  return {cmd, [folder, samples] {
    const io::SequenceReader seq(*folder);
    const io::SequenceSummary s = io::Summarize(seq, *samples);
    std::fputs(s.ToText(*folder).c_str(), stdout);
    for (const std::string& w : seq.sensor().warnings) std::fprintf(stderr, "info: warning: %s\n", Printable(w).c_str());
    return 0;
  }};
}

}  // namespace hdrf::cli
