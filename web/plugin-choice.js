// countershade's forced-choice trial as a jsPsych 8 plugin (docs/online-study.md). One trial runs a
// whole session: the app's trials, procedures and rows (the app's own code, through the
// WebAssembly engine), n images in a row at 1:1 device pixels or n intervals counted in display
// frames, every answer stored before the next trial appears, and a reload going on at the first
// trial without an answer with every procedure rebuilt from the stored rows.

import { ChoiceObserver, ChoiceSession, choiceColumns } from "./engine.js";
import { DeepImages } from "./deep-images.js";
import { buildPage, decodeImage, placeImages, rowLayout } from "./layout.js";
import { sessionPlugin } from "./session-plugin.js";
import { BROWSER_COLUMNS, SessionStore, browserFields } from "./store.js";

// The page's key names; with two alternatives Left and Right answer too.
const KEYS = { Enter: "enter", Escape: "escape", q: "q", Q: "q", 1: 0, 2: 1, 3: 2, 4: 3, ArrowLeft: "left", ArrowRight: "right" };
// The columns the page adds for a temporal trial: how long each interval was shown, in ms from the
// frame that showed it first to the frame that replaced it (requestAnimationFrame's times),
// ';'-separated; and "ok", or "mistimed" when one ran a frame or more long or short (that answer
// does not count, and the trial is shown again at once).
const TIMING_COLUMNS = ["interval_ms", "interval_timing"];

class ChoiceStudySession {
  constructor(root, engine, study, subject, session, environment, observer) {
    Object.assign(this, { study, subject, session, environment, choice: study.choice });
    this.columns = [...choiceColumns(engine), ...BROWSER_COLUMNS, ...TIMING_COLUMNS];
    this.run = new ChoiceSession(engine, study, subject, session);
    this.store = new SessionStore(window.localStorage, `countershade-choice:${study.set.sha256}:${subject}:${session}`,
                                  study.post_url, undefined, this.columns);
    this.store.headers = study.post_headers ?? {};
    this.store.flush(); // rows a reload left unsent
    this.resumed = this.store.rows.length > 0;
    const counted = this.store.rows.filter((row) => row.interval_timing !== "mistimed");
    if (this.resumed) this.run.replay(counted.map((row) => choiceColumns(engine).map((c) => row[c])));
    if (observer) this.observer = new ChoiceObserver(engine, observer, this.run);
    // Practice trials answered so far (the simulated observer's stream is keyed by it): a replay
    // has gone through all of them, as an uninterrupted session had.
    this.practiceIndex = this.resumed ? (study.forced_choice.practice_trials ?? 0) : 0;
    // A 16-bit study draws its images through the app's dither (main.js has checked for WebGL2).
    if (study.bits === 16) this.deep = new DeepImages(engine, root, this.run.native.sessionSeed());
    this.build(root);
  }

  build(root) {
    Object.assign(this, buildPage(root, this.study, 4));
  }

  now() {
    return (performance.now() - this.t0) / 1000;
  }

  // A new phase; its first frame is the next one drawn (frame()).
  enter(phase) {
    this.phase = phase;
    this.phaseSince = this.now();
    this.phaseFrame = null;
    this.frameTimes = []; // of the phase's frames, by frame number
    this.answerFrom = undefined;
  }

  // The trial after an answer (or the first): practice over, finished, or the next one.
  nextTrial() {
    this.enter(this.run.finished ? "finished" : "trial");
    this.trial = this.run.current;
  }

  // Which interval a temporal trial shows `frames` after it began: 0 … n − 1, −1 in a blank, n
  // once all are shown (as the app counts them).
  intervalAt(frames) {
    const { n_afc: n, interval_frames: shown, blank_frames: blank } = this.choice;
    const k = Math.floor(frames / (shown + blank));
    if (k >= n || (k === n - 1 && frames >= k * (shown + blank) + shown)) return n;
    return frames - k * (shown + blank) < shown ? k : -1;
  }

  // Whether an answer counts now: once the trial has been drawn, and in a temporal trial once its
  // last interval has been shown.
  answerAllowed() {
    if (this.phaseFrame === null || this.frameCount === this.phaseFrame) return false;
    return this.choice.layout === "spatial" || this.intervalAt(this.frameCount - this.phaseFrame) === this.choice.n_afc;
  }

  keyDown(e) {
    const key = KEYS[e.key];
    if (key === undefined) return;
    e.preventDefault();
    if (!e.repeat) this.press(key);
  }

  press(key) {
    if (this.phase === "instructions" || this.phase === "practice_done") {
      if (key === "enter") this.nextTrial();
    } else if (this.phase === "paused") {
      if (key === "q") this.end("quit");
      else if (key === "enter") this.enter(this.pausedFrom); // a paused trial starts again from its beginning
    } else if (this.phase === "finished") {
      if (key === "enter" || key === "escape") this.end("completed");
    } else if (this.phase === "trial") {
      if (key === "escape") return void ((this.pausedFrom = "trial"), this.enter("paused"));
      const response = typeof key === "number" ? key : this.choice.n_afc === 2 && key === "left" ? 0 : this.choice.n_afc === 2 && key === "right" ? 1 : null;
      if (response !== null && response < this.choice.n_afc && this.answerAllowed() && this.ready()) this.answer(response);
    }
  }

  answer(response) {
    const t = this.trial;
    // From when the answer is allowed: the trial's start, or (temporal) its question's first frame.
    const rt = this.now() - (this.choice.layout === "spatial" ? this.phaseSince : this.answerFrom);
    if (!t.practice && this.mistimed()) {
      this.record(this.run.rowWithoutAnswer(response, rt, new Date().toISOString()), "mistimed");
      return this.enter("trial"); // the same trial again, from its beginning
    }
    const { correct, row } = this.run.answer(response, rt, new Date().toISOString());
    if (t.practice) ++this.practiceIndex;
    else this.record(row);
    this.lastCorrect = correct;
    this.feedbackAfterPractice = t.practice;
    if (this.choice.feedback_frames > 0) return this.enter("feedback");
    this.afterAnswer(t.practice);
  }

  record(fields, timing = "ok") {
    const row = Object.fromEntries(fields.map((value, i) => [this.columns[i], value]));
    const temporal = this.choice.layout === "temporal";
    Object.assign(row, browserFields(this.environment, this.study.bits), {
      interval_ms: temporal ? this.intervalDurations().map((ms) => ms.toFixed(1)).join(";") : "",
      interval_timing: temporal ? timing : "",
    });
    this.store.add(row);
  }

  // Each interval's measured length in ms (temporal trials).
  intervalDurations() {
    const { n_afc: n, interval_frames: shown, blank_frames: blank } = this.choice;
    return Array.from({ length: n }, (_, k) => {
      const first = k * (shown + blank);
      return this.frameTimes[first + shown] - this.frameTimes[first];
    });
  }

  // Whether an interval of this temporal trial ran a frame or more long or short: its length off
  // by half a frame period or more (lengths come in whole periods), the period being the median
  // frame-to-frame time of the trial.
  mistimed() {
    if (this.choice.layout !== "temporal") return false;
    const times = this.frameTimes.filter((t) => t !== undefined);
    const steps = times.slice(1).map((t, i) => t - times[i]).sort((a, b) => a - b);
    const period = steps[Math.floor(steps.length / 2)];
    return this.intervalDurations().some((ms) => !(Math.abs(ms - this.choice.interval_frames * period) < period / 2));
  }

  afterAnswer(wasPractice) {
    if (wasPractice && !this.run.inPractice) return this.enter("practice_done");
    this.nextTrial();
  }

  // Each condition's images are decoded before its first trial (in the background, in order).
  async loadAll() {
    for (const [c, condition] of this.study.conditions.entries()) {
      await Promise.all([condition.reference, ...condition.images].map(async (file) => {
        this.decoded.set(file, await decodeImage(file, condition, this.deep));
      }));
      this.loaded.add(c);
    }
  }

  ready() {
    return this.loaded.has(this.trial.condition);
  }

  observe() {
    if (!this.observer || this.now() < this.phaseSince + this.observer.delay) return;
    if (this.phase === "trial" && this.ready() && this.answerAllowed())
      this.answer(this.observer.respond(this.trial, this.practiceIndex, this.choice.n_afc));
    else if (["instructions", "practice_done"].includes(this.phase)) this.press("enter");
    else if (this.phase === "finished") this.end("completed"); // as the app's automated runs end
  }

  draw() {
    const texts = this.choice.texts;
    const messages = {
      instructions: this.resumed ? "Welcome back. The session continues where it stopped.\n\nPress Enter to continue." : texts.welcome,
      practice_done: "The practice trials are over. The study itself begins now.\n\nPress Enter to continue.",
      paused: "Paused.\n\nPress Enter to resume, or Q to quit and save.",
      finished: "Thank you. All answers are saved.\n\nPress Enter to close.",
      feedback: this.lastCorrect ? "Correct" : "Wrong",
    };
    [this.header, this.question, this.hint].forEach((e) => (e.textContent = ""));
    placeImages(this.images, null, [], this.decoded, this.deep);
    if (this.phase !== "trial") return void (this.message.textContent = messages[this.phase]);
    if (!this.ready()) return void (this.message.textContent = "Loading the stimuli …");
    this.message.textContent = "";
    this.drawTrial();
  }

  drawTrial() {
    const t = this.trial, c = this.study.conditions[t.condition], n = this.choice.n_afc;
    const enhanced = c.images[t.lambda_index];
    const spatial = this.choice.layout === "spatial";
    const place = rowLayout(this.study, c, spatial ? n : 1, window.innerWidth, window.innerHeight, window.devicePixelRatio);
    if (!place) {
      this.message.textContent = "The window is too small to show the images at their true size. Please enlarge it, or set the browser's zoom to 100 %.";
      return;
    }
    const top = place.y / place.dpr, line = this.study.font_px * 1.35;
    this.header.style.top = `${top - 3.2 * line}px`;
    this.question.style.top = `${top - 1.9 * line}px`;
    this.hint.style.top = `${top + place.height / place.dpr + 0.8 * line}px`;
    this.header.textContent = t.practice ? "Practice" : `Trial ${t.number}`;
    let files = [];
    if (spatial) {
      files = Array.from({ length: n }, (_, i) => (i === t.target ? enhanced : c.reference));
      this.question.textContent = this.choice.texts.question;
      this.hint.textContent = `${this.choice.texts.answer_keys}: choose    Esc: pause`;
    } else {
      const interval = this.intervalAt(this.frameCount - this.phaseFrame);
      if (interval >= 0 && interval < n) files = [interval === t.target ? enhanced : c.reference];
      this.frameTimes[this.frameCount - this.phaseFrame] = this.frameTime;
      this.stallForTest(interval);
      if (interval >= 0 && interval < n) this.hint.textContent = `Interval ${interval + 1} of ${n}`;
      if (interval === n) {
        const which = n === 2 ? "Left or 1 the first, Right or 2 the second" : "1 the first"; // the app's words
        this.message.textContent = `${this.choice.texts.question}\n\n${this.choice.texts.answer_keys}: the interval (${which})`;
        this.answerFrom ??= this.now();
      }
    }
    placeImages(this.images, place, files, this.decoded, this.deep);
    window.countershadeShown = { trial: t.number, target: t.target, files, xs: place.xs, y: place.y };
  }

  // A test's fault: window.countershadeStallTrial = N holds trial N's first interval for 120 ms once,
  // as a busy machine would.
  stallForTest(interval) {
    if (window.countershadeStallTrial !== this.trial.number || interval !== 0 || this.stalled) return;
    this.stalled = true;
    for (const until = performance.now() + 120; performance.now() < until; );
  }

  frame(time) {
    if (this.ended) return;
    this.frameTime = time;
    if (this.phase === "feedback" && this.frameCount - this.phaseFrame >= this.choice.feedback_frames)
      this.afterAnswer(this.feedbackAfterPractice);
    // A phase counts its frames from the first one drawn; a trial's from the first one drawn with
    // its images loaded.
    if (this.phaseFrame === null) this.phaseFrame = this.frameCount;
    if (this.phase === "trial" && !this.ready()) this.phaseFrame = this.frameCount + 1;
    this.draw();
    this.deep?.drawNext();
    this.observe();
    ++this.frameCount;
    if (!this.ended) requestAnimationFrame((t) => this.frame(t));
  }

  start() {
    return new Promise((resolve) => {
      this.resolve = resolve;
      this.decoded = new Map();
      this.loaded = new Set();
      this.loadAll().catch((error) => (this.message.textContent = `A stimulus could not be loaded: ${error.message}`));
      this.t0 = performance.now();
      this.frameCount = 0;
      this.enter("instructions");
      this.onKeyDown = (e) => this.keyDown(e);
      document.addEventListener("keydown", this.onKeyDown);
      requestAnimationFrame((t) => this.frame(t));
    });
  }

  end(how) {
    this.ended = true;
    document.removeEventListener("keydown", this.onKeyDown);
    const result = { end: how, answers: this.store.rows.length, csv: this.store.csv() };
    window.countershadeResult = result;
    this.resolve(result);
  }
}

export const CountershadeChoicePlugin = sessionPlugin("countershade-choice", (page, engine, t) =>
  new ChoiceStudySession(page, engine, t.study, t.subject, t.session, t.environment, t.observer));
