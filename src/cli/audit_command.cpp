// `countershade audit`: measures a finished stimulus set and checks it for confounds.

#include <cstdio>
#include <memory>

#include "audit/audit.h"
#include "audit/audit_report.h"
#include "audit/bracket_check.h"
#include "cli/commands.h"
#include "cli/observer_viewing.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"

namespace countershade::cli {
namespace {

struct AuditArgs {
  std::string manifest, output;
  int jobs = 0;
  bool strict = false;
  ObserverViewingArgs viewing;
};

// The bracket check, when the viewing condition is known: from the flags, or the set's screen.
void check_brackets(const AuditArgs& args, AuditReport& report) {
  const Manifest manifest = read_manifest(args.manifest);
  if (args.viewing.display.empty() && args.viewing.ppd <= 0 && !manifest.viewing.pixels_per_degree)
    return;
  const ObserverViewing viewing =
      observer_viewing(args.viewing, "audit", manifest.viewing.pixels_per_degree);
  const auto prediction =
      predict_with_progress(manifest, args.manifest, viewing, args.jobs, "audit: predict");
  add_bracket_checks(report, prediction, manifest.lambda_grid, viewing.ppd);
}

}  // namespace

void add_audit_command(CLI::App& app) {
  using Args = AuditArgs;
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("audit",
                                     "Check a stimulus set for confounds: luminance drift, "
                                     "clipping, noise, λ = 0 against the reference.");
  cmd->add_option("manifest", args->manifest, "The set's manifest.json")->required();
  cmd->add_option("-o,--output", args->output,
                  "Report folder (report.html, audit.csv, audit.json, checks.csv)")
      ->required();
  cmd->add_option("--jobs", args->jobs, "Threads (default: all cores)")->check(CLI::Range(1, 1024));
  cmd->add_flag("--strict", args->strict, "Exit with status 1 when a check fails");
  add_observer_viewing_flags(cmd, args->viewing);
  cmd->callback([args] {
    check_output_folder(args->output);  // created by the report writer, after the audit succeeded
    Progress progress("audit");
    AuditOptions options;
    options.threads = args->jobs;
    options.progress = [&](double f) { progress.update(f); };
    AuditReport report = audit_stimulus_set(args->manifest, options);
    check_brackets(*args, report);
    write_audit_report(report, args->output);
    progress.finish(report.summary() + "; report in " + args->output + "/report.html");
    if (args->strict && report.failed() > 0) throw CommandFailed(report.summary(), 1);
  });
  cmd->footer(
      "Examples:\n"
      "  countershade audit stimuli/ritschel2008/manifest.json -o reports/audit-ritschel2008\n"
      "  countershade audit SET/manifest.json -o AUDIT --strict   # exit 1 when a check fails\n"
      "  countershade audit SET/manifest.json -o AUDIT --ppd 36   # also: does the grid bracket\n"
      "                                                           # the predicted thresholds?\n"
      "With --ppd, --display or a set made for a screen, the grid of each condition is checked\n"
      "against the image-computable observer's thresholds (docs/observer.md).");
}

}  // namespace countershade::cli
