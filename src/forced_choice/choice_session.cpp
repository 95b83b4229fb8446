#include "forced_choice/choice_session.h"

#include <cstdio>
#include <memory>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json_reader.h"
#include "core/time.h"
#include "forced_choice/choice_observer.h"
#include "forced_choice/choice_recorder.h"
#include "forced_choice/choice_run.h"
#include "observer/model_observer.h"
#include "runtime/image_decode.h"
#include "runtime/key_script.h"
#include "runtime/presenter.h"
#include "runtime/run_loop.h"
#include "runtime/signals.h"

namespace countershade::forced_choice {

namespace fs = std::filesystem;
using runtime::FrameContent;
using runtime::InputEvent;
using runtime::Key;
using runtime::RunEnd;
using json = nlohmann::ordered_json;

namespace {

// The configuration: --procedure, else the experiment's "forced_choice" block.
ChoiceConfig load_config(const ChoiceSessionOptions& o) {
  if (o.config) return parse_choice_config(parse_json_file(*o.config), o.config->string(), "");
  const nlohmann::json manifest = parse_json_file(o.manifest);
  if (!manifest.contains("experiment") || !manifest["experiment"].contains("forced_choice"))
    throw_input_error(o.manifest.string(),
                      "experiment.forced_choice: missing (add the block to the experiment, or pass "
                      "--procedure FILE)");
  return parse_choice_config(manifest["experiment"]["forced_choice"], o.manifest.string(),
                             "experiment.forced_choice");
}

runtime::DisplayOptions display_options(const ChoiceSessionOptions& o, const runtime::Study& study,
                                        const ChoiceConfig& config, uint64_t session_seed) {
  runtime::DisplayOptions d = runtime::study_display(study, "choose");
  d.columns = config.layout == Layout::spatial ? config.n_afc : 1;
  d.fullscreen = o.fullscreen;
  d.monitor = o.monitor;
  d.frame_clock = o.frame_clock;
  d.output_path = o.output_path;
  d.dither_seed = o.dither_seed.value_or(uint32_t(session_seed));
  return d;
}

// `choosing`: the blank surround while the next trial's procedure still chooses its stimulus
// (QUEST+ on a large grid), so that no frame waits for it.
enum class Phase { instructions, trial, feedback, practice_done, paused, finished, choosing };

constexpr Key kNumberKeys[] = {Key::one, Key::two, Key::three, Key::four};

// The alternative a key chooses (0-based), if it chooses one: a number key up to n, and with two
// alternatives also Left and Right.
std::optional<int> chosen(Key key, int n) {
  for (int i = 0; i < n; ++i)
    if (key == kNumberKeys[i]) return i;
  if (n == 2 && (key == Key::left || key == Key::right)) return key == Key::left ? 0 : 1;
  return std::nullopt;
}

// The observer an --observer spec names: a Weibull in λ, or the image-computable observer's
// prediction for each of the study's conditions (model:SEED).
ChoiceObserver choice_observer(const std::string& spec, const runtime::Study& study) {
  const auto model = observer::parse_model_observer(spec);
  if (!model) return parse_choice_observer(spec);
  std::vector<observer::ConditionName> names;
  for (const auto& c : study.conditions) names.push_back({c.scene, c.method, c.sigma});
  ChoiceObserver o;
  o.seed = model->seed;
  o.model = observer::probability_by_condition(
      observer::predict_conditions(study.manifest_path, names, *model, study.pixels_per_degree));
  return o;
}

// One run of a forced-choice session on the runtime's loop: key events drive the trials, each
// answer goes to the recorder.
class ChoiceLoop final : public runtime::RunLoop {
 public:
  ChoiceLoop(const ChoiceSessionOptions& o, const runtime::Study& study, const ChoiceConfig& config,
             ChoiceRun& run, ChoiceRecorder& recorder, runtime::Presenter& presenter,
             std::optional<ChoiceObserver> observer)
      : RunLoop(presenter, study, run_inputs(o)),
        o_(o),
        study_(study),
        config_(config),
        run_(run),
        recorder_(recorder),
        observer_(std::move(observer)) {
    // A resume has replayed the practice (it is not recorded): the simulated observer's answers
    // are keyed by the practice trials done, as in an uninterrupted run.
    if (o.resume) practice_index_ = config.practice_trials;
  }

 private:
  static runtime::RunInputs run_inputs(const ChoiceSessionOptions& o) {
    runtime::RunInputs in;
    if (o.script) in.script = runtime::ScriptedInput(runtime::parse_key_script(*o.script));
    in.scripted = o.script.has_value();
    in.observed = o.observer.has_value();
    in.screenshot = o.screenshot;
    return in;
  }

  void preloaded(const runtime::Preload& record) override {
    recorder_.current_run().preload = record;
    recorder_.save(run_);
  }

  void window_event(const runtime::WindowEvent& w, double t) override {
    if (w.kind == runtime::WindowEvent::Kind::press) press(w.key, t);
    if (w.kind == runtime::WindowEvent::Kind::focus_lost && phase_ == Phase::trial) pause(t);
  }

  void input(const InputEvent& e) override {
    if (e.kind == InputEvent::Kind::press) press(e.key, e.time_s);
  }

  // The simulated observer: Enter on every message screen, an answer once one is allowed.
  void observe(double now) override {
    if (now < phase_since_ + observer_->delay_s) return;
    if (phase_ == Phase::trial && answer_allowed(now)) {
      const ChoiceTrial& t = *run_.current();
      const int response = observer_->respond(t.number, practice_index_, t.lambda, t.target,
                                              config_.n_afc, t.condition);
      press(kNumberKeys[response], now);
    } else if (phase_ == Phase::instructions || phase_ == Phase::practice_done ||
               phase_ == Phase::finished) {
      press(Key::enter, now);
    }
  }

  // When the answer keys count: a spatial trial at once, a temporal one after its last interval.
  double answer_from() const {
    const int frames =
        config_.n_afc * config_.interval_frames + (config_.n_afc - 1) * config_.blank_frames;
    return config_.layout == Layout::spatial ? phase_since_
                                             : phase_since_ + frames / presenter().refresh_hz();
  }
  bool answer_allowed(double now) const { return now + 1e-9 >= answer_from(); }

  void enter_phase(Phase phase, double now) {
    phase_ = phase;
    phase_since_ = now;
  }

  void pause(double now) {
    paused_from_ = phase_;
    enter_phase(Phase::paused, now);
    recorder_.current_run().pauses.push_back({now, 0});
  }

  void press(Key key, double now) {
    note_press(now);
    switch (phase_) {
      case Phase::instructions:
        if (key == Key::enter) next_trial(now);
        break;
      case Phase::practice_done:
        if (key == Key::enter) next_trial(now);
        break;
      case Phase::feedback:
        break;
      case Phase::choosing:
        if (key == Key::escape) pause(now);
        break;
      case Phase::finished:
        if (key == Key::enter || key == Key::escape) end(RunEnd::completed);
        break;
      case Phase::paused:
        resume_or_quit(key, now);
        break;
      case Phase::trial:
        if (key == Key::escape)
          pause(now);
        else if (const auto choice = chosen(key, config_.n_afc); choice && answer_allowed(now))
          answer(*choice, now);
        break;
    }
  }

  void resume_or_quit(Key key, double now) {
    if (key == Key::quit) {
      recorder_.current_run().pauses.back().quit = true;
      end(RunEnd::quit);
    } else if (key == Key::enter) {
      recorder_.current_run().pauses.back().seconds =
          now - recorder_.current_run().pauses.back().at_s;
      enter_phase(paused_from_, now);  // a paused trial starts again from its beginning
      recorder_.save(run_);
    }
  }

  void answer(int response, double now) {
    const ChoiceTrial t = *run_.current();
    const bool was_practice = t.practice;
    const bool correct = run_.answer(response);
    if (!was_practice)
      recorder_.record(t, response, correct, now - answer_from());
    else
      ++practice_index_;
    last_correct_ = correct;
    feedback_after_practice_ = was_practice;
    recorder_.save(run_);
    if (config_.feedback_frames > 0) return enter_phase(Phase::feedback, now);
    after_answer(was_practice, now);
  }

  void after_answer(bool was_practice, double now) {
    if (was_practice && !run_.in_practice()) return enter_phase(Phase::practice_done, now);
    next_trial(now);
  }

  void next_trial(double now) {
    if (run_.finished()) return enter_phase(Phase::finished, now);
    enter_phase(run_.ready() ? Phase::trial : Phase::choosing, now);
  }

  void advance(double now) override {
    if (phase_ == Phase::choosing && run_.ready()) enter_phase(Phase::trial, now);
    if (phase_ == Phase::feedback &&
        now >= phase_since_ + config_.feedback_frames / presenter().refresh_hz())
      after_answer(feedback_after_practice_, now);
  }

  // The images of the current trial: (reference, enhanced) frames at `t`.
  std::pair<unsigned, unsigned> trial_textures(double t) const {
    const ChoiceTrial& trial = *run_.current();
    const auto& stimuli = study_.condition_images[size_t(trial.condition)];
    const int reference = study_.stimuli[size_t(stimuli[0])].frame_at(t);
    const int enhanced =
        study_.stimuli[size_t(stimuli[size_t(1 + trial.lambda_index)])].frame_at(t);
    return {textures()[size_t(reference)], textures()[size_t(enhanced)]};
  }

  FrameContent trial_content(double t) const {
    FrameContent c;
    const ChoiceTrial& trial = *run_.current();
    const auto [reference, enhanced] = trial_textures(t);
    c.image_width = study_.width(trial.condition);
    c.image_height = study_.height(trial.condition);
    c.header = trial.practice ? "Practice" : "Trial " + std::to_string(trial.number);
    c.question = config_.question;
    if (config_.layout == Layout::spatial) {
      for (int i = 0; i < config_.n_afc; ++i)
        c.row.push_back(i == trial.target ? enhanced : reference);
      c.hint = config_.answer_keys() + ": choose    Esc: pause";
      return c;
    }
    const int interval = interval_at((t - phase_since_) * presenter().refresh_hz());
    if (interval >= 0 && interval < config_.n_afc) {
      c.centred = true;
      c.left_texture = trial.target == interval ? enhanced : reference;
      c.hint = "Interval " + std::to_string(interval + 1) + " of " + std::to_string(config_.n_afc);
    } else if (interval == config_.n_afc) {
      c.message =
          config_.question + "\n\n" + config_.answer_keys() + ": the interval (" +
          (config_.n_afc == 2 ? "Left or 1 the first, Right or 2 the second" : "1 the first") + ")";
    }
    return c;
  }

  // Which interval a temporal trial shows `frames` after it began: 0 … n − 1, −1 in a blank, n
  // once all are shown.
  int interval_at(double frames) const {
    const int period = config_.interval_frames + config_.blank_frames;
    const int k = int(frames) / period;
    if (k >= config_.n_afc ||
        (k == config_.n_afc - 1 && frames >= k * period + config_.interval_frames))
      return config_.n_afc;
    return frames - k * period < config_.interval_frames ? k : -1;
  }

  FrameContent content(double t) const override {
    FrameContent c;
    switch (phase_) {
      case Phase::instructions:
        c.message = o_.resume ? "Welcome back. The session continues where it stopped.\n\nPress "
                                "Enter to continue."
                              : config_.welcome_text();
        break;
      case Phase::trial:
        return trial_content(t);
      case Phase::feedback:
        c.message = last_correct_ ? "Correct" : "Wrong";
        break;
      case Phase::choosing:
        break;
      case Phase::practice_done:
        c.message =
            "The practice trials are over. The study itself begins now.\n\nPress Enter to "
            "continue.";
        break;
      case Phase::paused:
        c.message = "Paused.\n\nPress Enter to resume, or Q to quit and save.";
        break;
      case Phase::finished:
        c.message = "Thank you. All answers are saved.\n\nPress Enter to close.";
        break;
    }
    return c;
  }

  void describe(const fs::path& shot, const FrameContent& content,
                const runtime::StimulusLayout& layout, double) const override {
    json info = {{"phase", int(phase_)}};
    if (phase_ == Phase::trial && (content.left_texture || !content.row.empty())) {
      const ChoiceTrial& trial = *run_.current();
      info["trial"] = trial.number;
      info["target"] = trial.target;
      auto file_of = [&](unsigned texture) {
        for (size_t i = 0; i < textures().size(); ++i)
          if (textures()[i] == texture) return study_.images[i].relative;
        return std::string();
      };
      const std::vector<unsigned> shown =
          content.centred ? std::vector<unsigned>{content.left_texture} : content.row;
      info["images"] = json::array();
      for (size_t i = 0; i < shown.size() && i < layout.xs.size(); ++i)
        info["images"].push_back({{"x", layout.xs[i]},
                                  {"y", layout.y},
                                  {"width", layout.width},
                                  {"height", layout.height},
                                  {"file", file_of(shown[i])}});
      info["interval"] = content.centred ? content.hint : "";
    }
    write_text_atomically(shot.string() + ".json", info.dump(2) + "\n");
  }

  const ChoiceSessionOptions& o_;
  const runtime::Study& study_;
  const ChoiceConfig& config_;
  ChoiceRun& run_;
  ChoiceRecorder& recorder_;
  std::optional<ChoiceObserver> observer_;
  Phase phase_ = Phase::instructions, paused_from_ = Phase::trial;
  double phase_since_ = 0;
  bool last_correct_ = false, feedback_after_practice_ = false;
  int practice_index_ = 0;
};

}  // namespace

int run_choice_session(const ChoiceSessionOptions& o) {
  runtime::check_subject_id(o.subject);
  if (o.session < 1 || o.session > 99) throw_input_error("--session", "must be between 1 and 99");
  if (o.script && o.observer) throw_input_error("--observer", "cannot be combined with --script");
  if (o.observer && !observer::parse_model_observer(*o.observer))
    parse_choice_observer(*o.observer);
  if (o.script) runtime::parse_key_script(*o.script);
  const runtime::Study study = runtime::load_study(o.manifest, std::nullopt);
  const ChoiceConfig config = load_config(o);
  runtime::verify_study_images(study);
  runtime::require_achromatic_images(study, o.output_path);
  std::optional<ChoiceObserver> observer;
  if (o.observer) observer = choice_observer(*o.observer, study);
  const uint64_t seed =
      runtime::session_seed(config.seed.value_or(study.manifest_seed), o.subject, o.session);
  ChoiceRun run(study, config, seed);
  std::error_code ec;
  if (!o.resume) fs::create_directories(o.sessions_dir, ec);
  ChoiceRecorder recorder(study, config, {o.subject, o.session, seed}, o.sessions_dir, o.resume,
                          run);
  if (run.finished()) {
    recorder.current_run().end = RunEnd::already_complete;
    recorder.save(run);
    std::printf("%s session %d is already complete: %d trials in %s\n", o.subject.c_str(),
                o.session, recorder.rows(), recorder.files().csv.string().c_str());
    return 0;
  }
  auto presenter = std::make_unique<runtime::Presenter>(display_options(o, study, config, seed));
  recorder.current_run().display = presenter->display_info();
  RunEnd end = RunEnd::running;
  {
    runtime::SignalGuard signals;
    ChoiceLoop loop(o, study, config, run, recorder, *presenter, std::move(observer));
    end = loop.run();
    recorder.current_run().frames = loop.frame_statistics();
    recorder.current_run().system_key_repeats_ignored = presenter->system_repeats_ignored();
  }
  recorder.current_run().end = end;
  recorder.current_run().ended_utc = utc_timestamp();
  recorder.save(run);
  presenter.reset();
  std::printf("%s session %d: %s; %d trials recorded in %s\n", o.subject.c_str(), o.session,
              runtime::run_end_name(end), recorder.rows(), recorder.files().csv.string().c_str());
  return 0;
}

}  // namespace countershade::forced_choice
