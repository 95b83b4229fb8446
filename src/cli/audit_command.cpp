// `countershade audit`: measures a finished stimulus set and checks it for confounds.

#include <cstdio>
#include <memory>

#include "audit/audit.h"
#include "audit/audit_report.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"

namespace countershade::cli {

void add_audit_command(CLI::App& app) {
  struct Args {
    std::string manifest, output;
    int jobs = 0;
    bool strict = false;
  };
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
  cmd->callback([args] {
    check_output_folder(args->output);  // created by the report writer, after the audit succeeded
    Progress progress("audit");
    AuditOptions options;
    options.threads = args->jobs;
    options.progress = [&](double f) { progress.update(f); };
    const AuditReport report = audit_stimulus_set(args->manifest, options);
    write_audit_report(report, args->output);
    progress.finish(report.summary() + "; report in " + args->output + "/report.html");
    if (args->strict && report.failed() > 0) throw CommandFailed(report.summary(), 1);
  });
  cmd->footer(
      "Examples:\n"
      "  countershade audit stimuli/ritschel2008/manifest.json -o reports/audit-ritschel2008\n"
      "  countershade audit SET/manifest.json -o AUDIT --strict   # exit 1 when a check fails");
}

}  // namespace countershade::cli
