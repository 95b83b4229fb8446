#include "adjust/session.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include <OpenImageIO/imageio.h>
#include <tbb/parallel_for.h>

#include "adjust/input_script.h"
#include "adjust/presenter.h"
#include "adjust/recorder.h"
#include "adjust/study.h"
#include "core/atomic_file.h"
#include "core/error.h"

namespace countershade::adjust {

namespace fs = std::filesystem;
using OrderedJson = nlohmann::ordered_json;

namespace {

std::atomic<int> g_signal{0};
void on_signal(int signal) { g_signal = signal; }

// Decodes an 8-bit stimulus into RGBA; the size must be the manifest's.
std::vector<uint8_t> decode_rgba(const StimulusImage& image) {
  auto in = OIIO::ImageInput::open(image.file.string());
  if (!in) throw_input_error(image.file.string(), "cannot read the image");
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width != image.width || spec.height != image.height)
    throw_input_error(image.file.string(), "the image size differs from the manifest");
  const int n = spec.nchannels;
  if (n < 1 || n > 4) throw_input_error(image.file.string(), "unsupported channel count " + std::to_string(n));
  std::vector<uint8_t> raw(size_t(spec.width) * size_t(spec.height) * size_t(n));
  if (!in->read_image(0, 0, 0, n, OIIO::TypeDesc::UINT8, raw.data()))
    throw_input_error(image.file.string(), "cannot decode: " + in->geterror());
  std::vector<uint8_t> rgba(size_t(spec.width) * size_t(spec.height) * 4, 255);
  for (size_t p = 0; p < size_t(spec.width) * size_t(spec.height); ++p) {
    const uint8_t* s = &raw[p * size_t(n)];
    uint8_t* d = &rgba[p * 4];
    if (n <= 2) d[0] = d[1] = d[2] = s[0];
    else d[0] = s[0], d[1] = s[1], d[2] = s[2];
    // Alpha is ignored on purpose: stimuli are shown opaque, exactly as their RGB values.
  }
  return rgba;
}

struct FrameTimes {
  std::vector<float> all, held;  // intervals in seconds
  std::vector<float> draw;       // time to build, render and swap a frame
  std::vector<double> dropped_at;  // session time of the first dropped frames
  std::vector<float> key_to_frame;  // from a key press to the swap of the frame that shows it

  // period > 0: also counts the values over 1.2 periods as dropped frames.
  static OrderedJson summary(std::vector<float> v, double period) {
    OrderedJson j = {{"count", v.size()}};
    if (v.empty()) return j;
    std::sort(v.begin(), v.end());
    double sum = 0;
    for (float x : v) sum += x;
    auto pct = [&](double p) { return 1000.0 * v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))]; };
    j["mean_ms"] = 1000.0 * sum / double(v.size());
    j["median_ms"] = pct(0.5);
    j["p95_ms"] = pct(0.95);
    j["p99_ms"] = pct(0.99);
    j["max_ms"] = 1000.0 * v.back();
    if (period > 0) j["dropped"] = std::count_if(v.begin(), v.end(), [&](float x) { return x > 1.2 * period; });
    return j;
  }
};

std::string screenshot_path(const fs::path& base, int count) {
  if (count == 0) return base.string();
  return (base.parent_path() / (base.stem().string() + "-" + std::to_string(count + 1) + base.extension().string())).string();
}

}  // namespace

int run_session(const SessionOptions& o) {
  // Everything that can be wrong with the input is found here, before any window opens.
  check_subject_id(o.subject);
  if (o.session < 1 || o.session > 99) throw_input_error("--session", "must be between 1 and 99");
  if (o.script && o.observer) throw_input_error("--observer", "cannot be combined with --script");
  std::vector<InputEvent> script;
  if (o.script) script = parse_key_script(*o.script);
  std::optional<uint64_t> observer_seed;
  if (o.observer) observer_seed = parse_observer_spec(*o.observer);
  if (o.screenshot && lower_extension(*o.screenshot) != ".png") throw_input_error(o.screenshot->string(), "screenshots are PNG files");
  Study study = load_study(o.manifest, o.config);
  verify_study_images(study);

  PlanSettings settings = study.config.plan;
  settings.seed = session_seed(study.config.seed.value_or(study.manifest_seed), o.subject, o.session);
  const std::vector<Trial> plan = plan_trials(study.conditions, settings);

  std::error_code ec;
  if (!o.resume) {
    fs::create_directories(o.sessions_dir, ec);
    if (!fs::is_directory(o.sessions_dir, ec)) throw_input_error(o.sessions_dir.string(), "cannot create the sessions folder");
  }
  if (fs::is_directory(o.sessions_dir, ec) && ::access(o.sessions_dir.c_str(), W_OK) != 0)
    throw_input_error(o.sessions_dir.string(), "the sessions folder is not writable");
  const bool new_session = !o.resume;
  SessionRecorder recorder(study, plan, {o.subject, o.session, settings.seed}, o.sessions_dir, o.resume);
  const SessionFiles files = recorder.files();
  auto discard_if_empty = [&] {
    if (new_session && recorder.run()["answers"] == 0)
      for (const auto& p : {files.csv, files.sidecar, files.keys}) fs::remove(p, ec);
  };

  Procedure procedure(study.conditions, plan, study.config.timing);
  if (o.resume) procedure.resume(recorder.recorded().answered);
  const int total_questions = procedure.real_trial_count() * kQuestionCount;
  if (procedure.done()) {
    recorder.run()["end"] = "already-complete";
    recorder.save();
    std::printf("%s session %d is already complete: %d of %d answers in %s\n", o.subject.c_str(), o.session,
                total_questions, total_questions, files.csv.string().c_str());
    return 0;
  }

  DisplayOptions display;
  display.fullscreen = o.fullscreen;
  display.monitor = o.monitor;
  display.stimulus_width = study.max_width();
  display.stimulus_height = study.max_height();
  display.gap_px = study.config.gap_px;
  display.surround = study.config.surround;
  display.font_px = study.config.font_px;
  display.title = "countershade adjust: " + study.set_name;
  std::unique_ptr<Presenter> presenter;
  try {
    presenter = std::make_unique<Presenter>(display);
  } catch (...) {
    recorder.run()["end"] = "display-failed";
    recorder.save();
    discard_if_empty();
    throw;
  }
  recorder.run()["display"] = presenter->display_info();

  g_signal = 0;
  auto old_term = std::signal(SIGTERM, on_signal);
  auto old_int = std::signal(SIGINT, on_signal);
  std::string end;
  try {
    // Preload every stimulus as a texture, decoding in parallel and uploading in batches.
    const double preload_start = presenter->now();
    std::vector<unsigned> texture(study.images.size());
    const size_t batch = 8;
    for (size_t first = 0; first < study.images.size() && end.empty(); first += batch) {
      const size_t last = std::min(first + batch, study.images.size());
      std::vector<std::vector<uint8_t>> pixels(last - first);
      tbb::parallel_for(first, last, [&](size_t i) { pixels[i - first] = decode_rgba(study.images[i]); });
      for (size_t i = first; i < last; ++i)
        texture[i] = presenter->upload_texture(pixels[i - first], study.images[i].width, study.images[i].height);
      FrameContent loading;
      loading.message = "Loading the stimuli: " + std::to_string(last) + " of " + std::to_string(study.images.size());
      loading.progress = double(last) / double(study.images.size());
      presenter->draw(loading);
      for (const auto& e : presenter->poll_events())
        if (e.kind == WindowEvent::Kind::close) end = "closed";
    }
    recorder.run()["preload"] = {{"images", study.images.size()}, {"seconds", presenter->now() - preload_start}};
    recorder.save();

    const double t0 = presenter->now();
    std::optional<SimulatedObserver> observer;
    if (observer_seed) observer.emplace(*observer_seed, study);
    const bool automated = o.script || observer;
    size_t next_script = 0;
    bool screenshot_due = false;
    int screenshots = 0;
    FrameTimes times;
    double last_frame = -1;
    int frame = 0;
    std::optional<double> pause_started;
    std::vector<double> pending_presses;  // presses not yet on screen

    auto log = [&](double t, const std::string& event, const std::string& key) { recorder.log_event(t, event, key, procedure); };
    // One trajectory line per auto-repeat step (a late frame can apply several at once).
    auto log_repeats = [&](double t, int index_before) {
      for (int k = std::abs(procedure.lambda_index() - index_before); k > 0; --k) log(t, "repeat", "");
    };
    auto handle = [&](const InputEvent& e) {
      switch (e.kind) {
        case InputEvent::Kind::screenshot: screenshot_due = true; return;
        case InputEvent::Kind::close: end = "closed"; return;
        case InputEvent::Kind::release: {
          const int index_before = procedure.lambda_index();
          procedure.release(e.key, e.time_s);  // may apply repeats that fell due before it
          log_repeats(e.time_s, index_before);
          log(e.time_s, "release", key_name(e.key));
          return;
        }
        case InputEvent::Kind::press: break;
      }
      pending_presses.push_back(e.time_s);
      const auto before = procedure.phase();
      if (before == Procedure::Phase::finished) {
        log(e.time_s, "press", key_name(e.key));
        if (e.key == Key::enter || e.key == Key::escape) end = "completed";
        return;
      }
      // Logged after the procedure took the key, so an arrow's line shows the new λ index.
      if (auto answer = procedure.press(e.key, e.time_s)) {
        recorder.record_answer(*answer, e.time_s);
        recorder.save();
      } else {
        log(e.time_s, "press", key_name(e.key));
      }
      const auto after = procedure.phase();
      if (after == Procedure::Phase::paused && before != after) {
        pause_started = e.time_s;
        log(e.time_s, "pause", "");
      } else if (before == Procedure::Phase::paused && after != before && after != Procedure::Phase::quit) {
        recorder.run()["pauses"].push_back({{"at_s", *pause_started}, {"seconds", e.time_s - *pause_started}});
        log(e.time_s, "resume", "");
        recorder.save();
      }
      if (after == Procedure::Phase::quit) {
        if (pause_started)
          recorder.run()["pauses"].push_back({{"at_s", *pause_started}, {"seconds", e.time_s - *pause_started}, {"quit", true}});
        end = "quit";
      }
    };

    while (end.empty()) {
      const double now = presenter->now() - t0;
      for (const auto& w : presenter->poll_events()) {
        const double t = w.time_s - t0;
        switch (w.kind) {
          case WindowEvent::Kind::press: handle({t, InputEvent::Kind::press, w.key}); break;
          case WindowEvent::Kind::release: handle({t, InputEvent::Kind::release, w.key}); break;
          case WindowEvent::Kind::close: end = "closed"; break;
          case WindowEvent::Kind::focus_gained: log(t, "focus-gained", ""); break;
          case WindowEvent::Kind::focus_lost:
            log(t, "focus-lost", "");
            recorder.run()["focus_losses"].push_back({{"at_s", t}, {"utc", utc_timestamp()}});
            // Another window took the keyboard: pause, so the trial does not run on unattended.
            if (procedure.phase() == Procedure::Phase::question) handle({t, InputEvent::Kind::press, Key::escape});
            recorder.save();
            break;
        }
      }
      while (next_script < script.size() && script[next_script].time_s <= now && end.empty()) handle(script[next_script++]);
      if (observer)
        for (const auto& e : observer->act(procedure, now)) handle(e);
      if (g_signal) end = g_signal == SIGTERM ? "terminated" : "interrupted";
      if (!end.empty()) break;

      const int index_before = procedure.lambda_index();
      procedure.tick(now);
      log_repeats(now, index_before);

      FrameContent content;
      const Instructions& text = study.config.text;
      switch (procedure.phase()) {
        case Procedure::Phase::instructions: content.message = o.resume ? text.resume : text.welcome; break;
        case Procedure::Phase::practice_done: content.message = text.practice_done; break;
        case Procedure::Phase::paused: content.message = text.paused; break;
        case Procedure::Phase::finished: content.message = text.finished; break;
        case Procedure::Phase::quit: break;
        case Procedure::Phase::question: {
          const Trial& trial = procedure.trial();
          const auto& images = study.condition_images[size_t(trial.condition)];
          const unsigned reference = texture[size_t(images[0])];
          const unsigned enhanced = texture[size_t(images[size_t(1 + procedure.lambda_index())])];
          content.left_texture = trial.side == Side::left ? enhanced : reference;
          content.right_texture = trial.side == Side::left ? reference : enhanced;
          content.image_width = study.width(trial.condition);
          content.image_height = study.height(trial.condition);
          content.header = trial.practice ? text.practice
                                          : "Trial " + std::to_string(trial.number) + " of " +
                                                std::to_string(procedure.real_trial_count());
          content.question = text.questions[int(procedure.question())];
          content.hint = text.keys_hint;
          break;
        }
      }
      fs::path shot;
      if (screenshot_due && o.screenshot) shot = screenshot_path(*o.screenshot, screenshots);
      const double draw_start = presenter->now();
      const StimulusLayout layout = presenter->draw(content, shot);
      const double draw_seconds = presenter->now() - draw_start;
      // The frame just swapped is the first to show these presses.
      for (double pressed : pending_presses) times.key_to_frame.push_back(float(presenter->now() - t0 - pressed));
      pending_presses.clear();
      if (!shot.empty()) {
        OrderedJson info = {{"frame", frame}, {"phase", int(procedure.phase())}};
        if (procedure.phase() == Procedure::Phase::question) {
          const Trial& trial = procedure.trial();
          const auto& images = study.condition_images[size_t(trial.condition)];
          const std::string ref = study.images[size_t(images[0])].relative;
          const std::string enh = study.images[size_t(images[size_t(1 + procedure.lambda_index())])].relative;
          info["trial"] = trial.number;
          info["question"] = kQuestionNames[int(procedure.question())];
          info["lambda_index"] = procedure.lambda_index();
          info["side"] = side_name(trial.side);
          info["left"] = {{"x", layout.left_x}, {"y", layout.y}, {"width", layout.width}, {"height", layout.height},
                          {"file", trial.side == Side::left ? enh : ref}};
          info["right"] = {{"x", layout.right_x}, {"y", layout.y}, {"width", layout.width}, {"height", layout.height},
                           {"file", trial.side == Side::left ? ref : enh}};
        }
        write_text_atomically(shot.string() + ".json", info.dump(2) + "\n");
        ++screenshots;
        screenshot_due = false;
      }
      presenter->pace();
      const double t = presenter->now();
      if (last_frame >= 0 && frame > 20) {  // the first frames calibrate the pacing
        const double interval = t - last_frame;
        times.all.push_back(float(interval));
        times.draw.push_back(float(draw_seconds));
        if (procedure.key_held()) times.held.push_back(float(interval));
        if (interval > 1.2 / presenter->refresh_hz() && times.dropped_at.size() < 100) times.dropped_at.push_back(t - t0);
      }
      last_frame = t;
      ++frame;

      if (automated && procedure.phase() == Procedure::Phase::finished) end = "completed";
      if (o.script && !observer && next_script == script.size() && end.empty()) end = "script-ended";
    }
    const double period = 1.0 / presenter->refresh_hz();
    recorder.run()["frames"] = {{"pacing", presenter->timer_paced() ? "timer" : "vsync"},
                                {"period_ms", 1000 * period},
                                {"dropped_threshold_ms", 1200 * period},
                                {"all", FrameTimes::summary(times.all, period)},
                                {"key_held", FrameTimes::summary(times.held, period)},
                                {"draw", FrameTimes::summary(times.draw, period)},
                                {"dropped_at_s", times.dropped_at},
                                {"key_to_frame", FrameTimes::summary(times.key_to_frame, 0)}};
    recorder.run()["system_key_repeats_ignored"] = presenter->system_repeats_ignored();
  } catch (const std::exception& e) {
    recorder.run()["end"] = std::string("error: ") + e.what();
    recorder.run()["ended_utc"] = utc_timestamp();
    recorder.save();
    std::signal(SIGTERM, old_term);
    std::signal(SIGINT, old_int);
    throw;
  }
  std::signal(SIGTERM, old_term);
  std::signal(SIGINT, old_int);
  recorder.run()["end"] = end;
  recorder.run()["ended_utc"] = utc_timestamp();
  recorder.save();
  presenter.reset();
  const int answered = procedure.answered_count();
  std::printf("%s session %d: %s; %d of %d answers recorded in %s\n", o.subject.c_str(), o.session, end.c_str(),
              answered, total_questions, files.csv.string().c_str());
  return 0;
}

}  // namespace countershade::adjust
