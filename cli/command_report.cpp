// `blocklab report RUN_DIR... --out DIR`: the command line of experiments/report.h (write_report), with progress and
// an ETA on stderr. `blocklab report --readme-tables configs/papers/<paper>` prints the generated README tables of
// one paper folder (published.yaml beside measured/<table>.jsonl; scripts/update_paper_tables.py pastes them and
// tests/cli/test_cli_paper_tables.sh fails while a README differs). docs/report.md describes the page.
#include <iostream>

#include "cli/commands.h"
#include "cli/progress.h"
#include "core/error.h"
#include "experiments/report.h"

namespace blocklab::cli {

int run_report(const ReportArgs& args) {
  if (!args.readme_tables.empty()) {
    if (!args.run_dirs.empty() || !args.out_dir.empty())
      fail("report", "--readme-tables prints one paper folder's tables; it takes no run folders and no --out");
    std::cout << paper_readme_tables(args.readme_tables);
    return 0;
  }
  ReportSettings settings;
  settings.run_dirs = args.run_dirs;
  settings.out_dir = args.out_dir;
  settings.papers_dir = args.papers_dir.empty() ? std::string(BLOCKLAB_SOURCE_DIR) + "/configs/papers" : args.papers_dir;
  settings.thumbnail_size = args.thumbnail_size;
  settings.thumbnail_images = args.thumbnail_images;
  ProgressDisplay display(!args.quiet, "thumbnails");
  write_report(settings, [&](std::size_t done, std::size_t total, const std::string& current) {
    display.update(done, total, 0, current);
  });
  display.finish();
  std::cout << "wrote " << args.out_dir << "/index.html and " << args.out_dir << "/report.md\n";
  return 0;
}

}  // namespace blocklab::cli
