#include "adjust/session.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "adjust/recorder.h"
#include "adjust/simulated_observer.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/time.h"
#include "observer/model_observer.h"
#include "runtime/image_decode.h"
#include "runtime/key_script.h"
#include "runtime/presenter.h"
#include "runtime/run_loop.h"
#include "runtime/session_run.h"
#include "runtime/signals.h"
#include "runtime/study.h"

namespace countershade::adjust {

// From the study runtime (src/runtime).
using runtime::check_subject_id;
using runtime::DisplayOptions;
using runtime::FrameContent;
using runtime::InputEvent;
using runtime::key_name;
using runtime::load_study;
using runtime::parse_key_script;
using runtime::Preload;
using runtime::Presenter;
using runtime::require_achromatic_images;
using runtime::run_end_name;
using runtime::RunEnd;
using runtime::session_seed;
using runtime::StimulusLayout;
using runtime::Study;
using runtime::study_display;
using runtime::verify_study_images;
using runtime::WindowEvent;

namespace fs = std::filesystem;
using OrderedJson = nlohmann::ordered_json;

namespace {

// What can be wrong with the command's own inputs, found before anything else.
struct CheckedInputs {
  std::vector<InputEvent> script;
  std::optional<uint64_t> observer_seed;
  std::optional<observer::ModelObserverSpec> model;  // --observer model:SEED
  SimulatedObserver::PredictedLevels predicted;      // the model's, once the study is loaded
};

CheckedInputs check_inputs(const SessionOptions& o) {
  check_subject_id(o.subject);
  if (o.session < 1 || o.session > 99) throw_input_error("--session", "must be between 1 and 99");
  if (o.script && o.observer) throw_input_error("--observer", "cannot be combined with --script");
  if (o.frame_clock && !o.script && !o.observer)
    throw_input_error("--frame-clock",
                      "needs --script or --observer (a person needs the real clock)");
  CheckedInputs in;
  if (o.script) in.script = parse_key_script(*o.script);
  if (o.observer) {
    in.model = observer::parse_model_observer(*o.observer);
    in.observer_seed = in.model ? in.model->seed : parse_observer_spec(*o.observer);
  }
  if (o.screenshot) check_output_file(*o.screenshot, {".png"}, "a PNG file (screenshots are PNG)");
  return in;
}

void check_sessions_dir(const SessionOptions& o) {
  std::error_code ec;
  if (!o.resume) {
    fs::create_directories(o.sessions_dir, ec);
    if (!fs::is_directory(o.sessions_dir, ec))
      throw_input_error(o.sessions_dir.string(), "cannot create the sessions folder");
  }
  if (fs::is_directory(o.sessions_dir, ec) && ::access(o.sessions_dir.c_str(), W_OK) != 0)
    throw_input_error(o.sessions_dir.string(), "the sessions folder is not writable");
}

DisplayOptions display_options(const SessionOptions& o, const Study& study, uint64_t session_seed) {
  DisplayOptions display = study_display(study, "adjust");
  display.fullscreen = o.fullscreen;
  display.monitor = o.monitor;
  display.frame_clock = o.frame_clock;
  display.monitor_width_mm = o.monitor_width_mm;
  display.output_path = o.output_path;
  display.dither_seed = o.dither_seed.value_or(uint32_t(session_seed));
  return display;
}

// One run of the adjustment procedure on the runtime's loop: key events go to the procedure,
// answers to the recorder, and every key and λ step to the trajectory.
class SessionLoop final : public runtime::RunLoop {
 public:
  SessionLoop(const SessionOptions& o, const Study& study, Procedure& procedure,
              SessionRecorder& recorder, Presenter& presenter, CheckedInputs inputs)
      : RunLoop(presenter, study, run_inputs(o, inputs)),
        o_(o),
        study_(study),
        procedure_(procedure),
        recorder_(recorder) {
    if (inputs.observer_seed)
      observer_.emplace(*inputs.observer_seed, study, 0.02, std::move(inputs.predicted));
  }

 private:
  static runtime::RunInputs run_inputs(const SessionOptions& o, CheckedInputs& inputs) {
    return {runtime::ScriptedInput(std::move(inputs.script)), o.script.has_value(),
            inputs.observer_seed.has_value(), o.screenshot};
  }

  void preloaded(const Preload& record) override {
    recorder_.run().preload = record;
    recorder_.save();
  }

  void observe(double now) override {
    for (const auto& e : observer_->act(procedure_, now)) input(e);
  }

  void advance(double now) override {
    const int index_before = procedure_.lambda_index();
    procedure_.tick(now);
    log_repeats(now, index_before);
  }

  bool key_held() const override { return procedure_.key_held(); }
  bool finished_unattended() const override {
    return procedure_.phase() == Procedure::Phase::finished;
  }

  void log(double t, const std::string& event, const std::string& key) {
    recorder_.log_event(t, event, key, procedure_);
  }
  // One trajectory line per auto-repeat step (a late frame can apply several at once).
  void log_repeats(double t, int index_before) {
    for (int k = std::abs(procedure_.lambda_index() - index_before); k > 0; --k)
      log(t, "repeat", "");
  }

  void window_event(const WindowEvent& w, double t) override {
    switch (w.kind) {
      case WindowEvent::Kind::press:
        input({t, InputEvent::Kind::press, w.key});
        break;
      case WindowEvent::Kind::release:
        input({t, InputEvent::Kind::release, w.key});
        break;
      case WindowEvent::Kind::close:  // the loop ends the run
        break;
      case WindowEvent::Kind::focus_gained:
        log(t, "focus-gained", "");
        break;
      case WindowEvent::Kind::focus_lost:
        log(t, "focus-lost", "");
        recorder_.run().focus_losses.push_back({t, utc_timestamp()});
        // Another window took the keyboard: pause, so the trial does not run on unattended.
        if (procedure_.phase() == Procedure::Phase::question)
          input({t, InputEvent::Kind::press, Key::escape});
        recorder_.save();
        break;
    }
  }

  void input(const InputEvent& e) override {
    switch (e.kind) {
      case InputEvent::Kind::screenshot:  // the loop takes these
      case InputEvent::Kind::close:
        return;
      case InputEvent::Kind::release: {
        const int index_before = procedure_.lambda_index();
        procedure_.release(e.key, e.time_s);  // may apply repeats that fell due before it
        log_repeats(e.time_s, index_before);
        log(e.time_s, "release", key_name(e.key));
        return;
      }
      case InputEvent::Kind::press:
        press(e);
        return;
    }
  }

  void press(const InputEvent& e) {
    note_press(e.time_s);
    const auto before = procedure_.phase();
    if (before == Procedure::Phase::finished) {
      log(e.time_s, "press", key_name(e.key));
      if (e.key == Key::enter || e.key == Key::escape) end(RunEnd::completed);
      return;
    }
    // Logged after the procedure took the key, so an arrow's line shows the new λ index.
    if (auto answer = procedure_.press(e.key, e.time_s)) {
      recorder_.record_answer(*answer, e.time_s);
      recorder_.save();
    } else {
      log(e.time_s, "press", key_name(e.key));
    }
    track_pause(before, procedure_.phase(), e.time_s);
  }

  void track_pause(Procedure::Phase before, Procedure::Phase after, double t) {
    if (after == Procedure::Phase::paused && before != after) {
      pause_started_ = t;
      log(t, "pause", "");
    } else if (before == Procedure::Phase::paused && after != before &&
               after != Procedure::Phase::quit) {
      recorder_.run().pauses.push_back({*pause_started_, t - *pause_started_});
      log(t, "resume", "");
      recorder_.save();
    }
    if (after == Procedure::Phase::quit) {
      if (pause_started_)
        recorder_.run().pauses.push_back({*pause_started_, t - *pause_started_, true});
      end(RunEnd::quit);
    }
  }

  // The images the current question shows `t` seconds into the session: (reference, enhanced),
  // a sequence's frames both from the same clock.
  std::pair<int, int> question_images(double t) const {
    const auto& stimuli = study_.condition_images[size_t(procedure_.trial().condition)];
    return {study_.stimuli[size_t(stimuli[0])].frame_at(t),
            study_.stimuli[size_t(stimuli[size_t(1 + procedure_.lambda_index())])].frame_at(t)};
  }

  FrameContent content(double t) const override {
    FrameContent content;
    const procedures::Instructions& text = study_.config.text;
    switch (procedure_.phase()) {
      case Procedure::Phase::instructions:
        content.message = o_.resume ? text.resume : text.welcome;
        break;
      case Procedure::Phase::practice_done:
        content.message = text.practice_done;
        break;
      case Procedure::Phase::paused:
        content.message = text.paused;
        break;
      case Procedure::Phase::finished:
        content.message = text.finished;
        break;
      case Procedure::Phase::quit:
        break;
      case Procedure::Phase::question: {
        const Trial& trial = procedure_.trial();
        const auto [reference, enhanced] = question_images(t);
        content.left_texture = textures()[size_t(trial.side == Side::left ? enhanced : reference)];
        content.right_texture = textures()[size_t(trial.side == Side::left ? reference : enhanced)];
        content.image_width = study_.width(trial.condition);
        content.image_height = study_.height(trial.condition);
        content.header = trial.practice ? text.practice
                                        : "Trial " + std::to_string(trial.number) + " of " +
                                              std::to_string(procedure_.real_trial_count());
        content.question = text.questions[int(procedure_.question())];
        content.hint = text.keys_hint;
        break;
      }
    }
    return content;
  }

  // The screenshot's sidecar: what was on screen and where.
  void describe(const fs::path& shot, const FrameContent&, const StimulusLayout& layout,
                double t) const override {
    // output_frame: the frame index the dither used (16-bit sets), counted from the window's first
    // frame.
    OrderedJson info = {{"frame", frames_drawn()},
                        {"output_frame", presenter().frames_drawn() - 1},
                        {"phase", int(procedure_.phase())}};
    if (procedure_.phase() == Procedure::Phase::question) {
      const Trial& trial = procedure_.trial();
      const auto [reference, enhanced] = question_images(t);
      const std::string ref = study_.images[size_t(reference)].relative;
      const std::string enh = study_.images[size_t(enhanced)].relative;
      info["trial"] = trial.number;
      info["question"] = kQuestionNames[int(procedure_.question())];
      info["lambda_index"] = procedure_.lambda_index();
      info["side"] = side_name(trial.side);
      info["left"] = {{"x", layout.left_x},
                      {"y", layout.y},
                      {"width", layout.width},
                      {"height", layout.height},
                      {"file", trial.side == Side::left ? enh : ref}};
      info["right"] = {{"x", layout.right_x},
                       {"y", layout.y},
                       {"width", layout.width},
                       {"height", layout.height},
                       {"file", trial.side == Side::left ? ref : enh}};
    }
    write_text_atomically(shot.string() + ".json", info.dump(2) + "\n");
  }

  const SessionOptions& o_;
  const Study& study_;
  Procedure& procedure_;
  SessionRecorder& recorder_;
  std::optional<SimulatedObserver> observer_;
  std::optional<double> pause_started_;
};

// Opens the window; a failure is recorded, and a new session without answers leaves no files.
std::unique_ptr<Presenter> open_window(const SessionOptions& o, const Study& study,
                                       SessionRecorder& recorder, uint64_t session_seed) {
  try {
    return std::make_unique<Presenter>(display_options(o, study, session_seed));
  } catch (...) {
    recorder.run().end = RunEnd::display_failed;
    recorder.save();
    if (!o.resume && recorder.run().answers == 0) {
      std::error_code ec;
      for (const auto& p : {recorder.files().csv, recorder.files().sidecar, recorder.files().keys})
        fs::remove(p, ec);
    }
    throw;
  }
}

// Runs the session's loop with the signal handlers installed; records the frame statistics, or
// the error that ended it (then rethrown).
RunEnd run_loop(const SessionOptions& o, const Study& study, Procedure& procedure,
                SessionRecorder& recorder, Presenter& presenter, CheckedInputs inputs) {
  runtime::SignalGuard signals;
  SessionLoop loop(o, study, procedure, recorder, presenter, std::move(inputs));
  RunEnd end = RunEnd::running;
  try {
    end = loop.run();
  } catch (const std::exception& e) {
    recorder.run().end = RunEnd::error;
    recorder.run().error = e.what();
    recorder.run().ended_utc = utc_timestamp();
    recorder.save();
    throw;
  }
  recorder.run().frames = loop.frame_statistics();
  recorder.run().system_key_repeats_ignored = presenter.system_repeats_ignored();
  return end;
}

// The image-computable observer's λ at 1, 2 and 4 JND for each of the study's conditions.
SimulatedObserver::PredictedLevels predicted_levels(const Study& study,
                                                    const observer::ModelObserverSpec& spec) {
  std::vector<observer::ConditionName> names;
  for (const auto& c : study.conditions) names.push_back({c.scene, c.method, c.sigma});
  SimulatedObserver::PredictedLevels levels;
  for (const auto& p :
       observer::predict_conditions(study.manifest_path, names, spec, study.pixels_per_degree))
    levels.push_back(p.lambda_at);
  return levels;
}

}  // namespace

int run_session(const SessionOptions& o) {
  // Everything that can be wrong with the input is found here, before any window opens.
  CheckedInputs inputs = check_inputs(o);
  Study study = load_study(o.manifest, o.config);
  verify_study_images(study);
  require_achromatic_images(study, o.output_path);
  if (inputs.model) inputs.predicted = predicted_levels(study, *inputs.model);
  PlanSettings settings = study.config.plan;
  settings.seed =
      session_seed(study.config.seed.value_or(study.manifest_seed), o.subject, o.session);
  const std::vector<Trial> plan = plan_trials(study.conditions, settings);
  check_sessions_dir(o);
  SessionRecorder recorder(study, plan, {o.subject, o.session, settings.seed}, o.sessions_dir,
                           o.resume);

  Procedure procedure(study.conditions, plan, study.config.timing);
  if (o.resume) procedure.resume(recorder.recorded().answered);
  const int total_questions = procedure.real_trial_count() * kQuestionCount;
  if (procedure.done()) {
    recorder.run().end = RunEnd::already_complete;
    recorder.save();
    std::printf("%s session %d is already complete: %d of %d answers in %s\n", o.subject.c_str(),
                o.session, total_questions, total_questions, recorder.files().csv.string().c_str());
    return 0;
  }
  std::unique_ptr<Presenter> presenter = open_window(o, study, recorder, settings.seed);
  recorder.run().display = presenter->display_info();
  const RunEnd end = run_loop(o, study, procedure, recorder, *presenter, std::move(inputs));
  recorder.run().end = end;
  recorder.run().ended_utc = utc_timestamp();
  recorder.save();
  presenter.reset();
  std::printf("%s session %d: %s; %d of %d answers recorded in %s\n", o.subject.c_str(), o.session,
              run_end_name(end), procedure.answered_count(), total_questions,
              recorder.files().csv.string().c_str());
  return 0;
}

}  // namespace countershade::adjust
