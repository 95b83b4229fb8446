// `countershade export-web`: a stimulus set as a static web study (docs/online-study.md).

#include <cstdio>
#include <cstdlib>
#include <memory>

#include "adjust/web_export.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json_reader.h"
#include "forced_choice/choice_run.h"
#include "observer/model_observer.h"

namespace countershade::cli {
namespace {

struct ExportArgs {
  std::string manifest, output, post_url, title, assets, study;
  bool chinrest = false;
  double model_ppd = 0;  // 0: no prediction in the page
};

// The folder with node_modules/ and web/: --assets, else $COUNTERSHADE_WEB_ASSETS, else the
// source tree the program was built from.
std::string assets_folder(const ExportArgs& a) {
  if (!a.assets.empty()) return a.assets;
  if (const char* env = std::getenv("COUNTERSHADE_WEB_ASSETS")) return env;
  return COUNTERSHADE_WEB_ASSETS;
}

// The WebAssembly engine's folder: $COUNTERSHADE_WEB_ENGINE, else the build that made the program.
std::string engine_folder() {
  if (const char* env = std::getenv("COUNTERSHADE_WEB_ENGINE")) return env;
  return COUNTERSHADE_WEB_ENGINE;
}

// The forced-choice study, when the page is to run it: --study, else whether the experiment has a
// forced_choice block.
std::optional<adjust::WebChoiceStudy> choice_study(const ExportArgs& a) {
  const nlohmann::json manifest = parse_json_file(a.manifest);
  const nlohmann::json* block = nullptr;
  if (manifest.contains("experiment") && manifest["experiment"].contains("forced_choice"))
    block = &manifest["experiment"]["forced_choice"];
  if (a.study == "adjust" || (a.study.empty() && !block)) return std::nullopt;
  if (!block)
    throw_input_error(a.manifest + ": experiment.forced_choice",
                      "missing, so the set has no forced-choice study to export");
  return adjust::WebChoiceStudy{
      *block, procedures::parse_choice_config(*block, a.manifest, "experiment.forced_choice")};
}

// The prediction the page's model observers answer from (?observer=model:SEED).
nlohmann::json page_model(const runtime::Study& study, double ppd) {
  std::vector<observer::ConditionName> names;
  for (const auto& c : study.conditions) names.push_back({c.scene, c.method, c.sigma});
  return observer::model_json(
      observer::predict_conditions(study.manifest_path, names, {0, ppd}, std::nullopt));
}

void run(const ExportArgs& a) {
  check_output_folder(a.output);
  if (!a.post_url.empty() && a.post_url.rfind("http://", 0) != 0 &&
      a.post_url.rfind("https://", 0) != 0 && a.post_url.rfind("/", 0) != 0)
    throw_input_error(
        "--post-url",
        "must start with http://, https:// or / (a path on the server that hosts the study)");
  const runtime::Study study = runtime::load_study(a.manifest, std::nullopt);
  adjust::WebExportOptions o;
  o.output = a.output;
  o.assets = assets_folder(a);
  o.engine = engine_folder();
  if (!a.post_url.empty()) o.post_url = a.post_url;
  o.chinrest = a.chinrest;
  o.title = a.title;
  o.forced_choice = choice_study(a);
  if (o.forced_choice)  // the page starts every condition's procedure in its WebAssembly engine
    if (const auto problem = forced_choice::procedure_memory_problem(
            study, o.forced_choice->config, procedures::kWebAssemblyMemoryBytes / 2))
      throw_input_error(o.forced_choice->config.source + "procedure",
                        *problem + " in the browser (half its WebAssembly engine's memory)");
  if (a.model_ppd > 0) o.model = page_model(study, a.model_ppd);
  const size_t images = adjust::export_web_study(study, o);
  std::fprintf(
      stderr,
      "export-web: wrote %s (%s study, %zu images, %zu conditions); open it through a web server, "
      "e.g. `python3 -m http.server -d %s`\n",
      a.output.c_str(), o.forced_choice ? "forced-choice" : "adjustment", images,
      study.conditions.size(), a.output.c_str());
}

}  // namespace

void add_export_web_command(CLI::App& app) {
  auto a = std::make_shared<ExportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "export-web", "Export a stimulus set as a static jsPsych adjustment study for browsers.");
  cmd->add_option("manifest", a->manifest, "The stimulus set's manifest.json")->required();
  cmd->add_option("-o,--output", a->output, "The study folder to write")->required();
  cmd->add_option("--post-url", a->post_url,
                  "Also send every answer to this URL or /path on the hosting server (POST, one "
                  "CSV row), retried until acknowledged");
  cmd->add_flag("--chinrest", a->chinrest,
                "Add jsPsych's virtual chinrest (recorded only: the page is never rescaled)");
  cmd->add_option("--title", a->title, "The page title (default: the set's name)");
  cmd->add_option("--model-ppd", a->model_ppd,
                  "Embed the image-computable observer's prediction at these pixels per degree, "
                  "so that ?observer=model:SEED pilots the page (docs/observer.md)")
      ->check(within(1, 10000));
  cmd->add_option("--study", a->study,
                  "Which study the page runs: forced-choice (the experiment's forced_choice "
                  "block) or adjust (default: forced-choice when the experiment has the block)")
      ->check(CLI::IsMember({"adjust", "forced-choice"}));
  cmd->add_option("--assets", a->assets,
                  "The folder with node_modules/ and web/ (default: the source tree)");
  cmd->callback([a] { run(*a); });
  cmd->footer(
      "Example:\n  countershade export-web stimuli/cornsweet/manifest.json -o web-study\n"
      "  python3 -m http.server -d web-study 8000   # then open "
      "http://localhost:8000/?subject=P01");
}

}  // namespace countershade::cli
