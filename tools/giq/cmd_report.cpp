// `giq report DIR`: one self-contained HTML page from the gate, score and sweep outputs found
// under DIR (see report_inputs.h and report_page.h).

#include <iostream>
#include <memory>

#include "command.h"
#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "report_inputs.h"
#include "report_page.h"

namespace giq::cli {
namespace {

struct ReportArgs {
  std::string dir;
  std::string out;
  std::string title = "giq report";
  int max_frames = 60;
};

int run_report(const ReportArgs& a) {
  if (a.max_frames < 1)
    throw InputError("", "--max-frames", std::to_string(a.max_frames) + "; expected at least 1");
  const ReportInputs in = scan_report_inputs(a.dir, a.max_frames);
  const std::filesystem::path out =
      a.out.empty() ? std::filesystem::path(a.dir) / "report.html" : std::filesystem::path(a.out);
  write_file_atomically(out, report_html(in, a.title));
  std::cout << "giq report: " << in.comparisons.size() << " comparisons, "
            << (in.gate ? "gate results, " : "") << in.sweeps.size() << " sweeps, "
            << in.plots.size() << " plots"
            << (in.warnings.empty()
                    ? ""
                    : ", " + std::to_string(in.warnings.size()) + " files not shown")
            << " -> " << out.string() << '\n';
  return 0;
}

}  // namespace

void add_report_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<ReportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "report", "One self-contained HTML page from gate, score and sweep outputs");
  cmd->add_option("DIR", a->dir, "Folder holding giq gate / score / sweep outputs")->required();
  cmd->add_option("--out", a->out, "HTML file to write (default: DIR/report.html)");
  cmd->add_option("--title", a->title, "Page title")->capture_default_str();
  cmd->add_option("--max-frames", a->max_frames,
                  "Most sequence frames in a flip-book (sampled evenly)")
      ->capture_default_str();
  cmd->footer("Example: one page from a gate run's outputs:\n  giq report build/gate");
  cmd->callback([a, &exit_code] { exit_code = run_report(*a); });
}

}  // namespace giq::cli
