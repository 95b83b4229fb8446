// countershade's adjustment trial as a jsPsych 8 plugin (docs/online-study.md). One trial runs a
// whole session: the app's plan for the subject and seed, the app's procedure and key repeat (both
// the app's own code, through the WebAssembly engine), the images at 1:1 device pixels, every
// answer stored before the next question appears, and a reload resuming at the first unanswered
// question.

import { AdjustmentProcedure, QUESTIONS, SimulatedObserver, planSession, sessionSeed } from "./engine.js";
import { DeepImages } from "./deep-images.js";
import { buildPage, decodeImage, element, placeImages, rowLayout } from "./layout.js";
import { sessionPlugin } from "./session-plugin.js";
import { SessionStore, browserFields } from "./store.js";

const KEYS = { ArrowUp: "up", ArrowDown: "down", ArrowLeft: "left", ArrowRight: "right", Enter: "enter",
               Backspace: "backspace", Escape: "escape", q: "q", Q: "q" };

// Where the two images go, in device pixels, or null when the window is too small for 1:1.
export function layout(study, condition, innerWidth, innerHeight, dpr) {
  const place = rowLayout(study, condition, 2, innerWidth, innerHeight, dpr);
  return place && { ...place, left: place.xs[0], right: place.xs[1] };
}

class AdjustSession {
  constructor(root, engine, study, subject, session, environment, observer) {
    this.study = study;
    this.subject = subject;
    this.session = session;
    this.environment = environment;
    this.plan = planSession(engine, study, subject, session);
    this.procedure = new AdjustmentProcedure(engine, study, this.plan);
    this.store = new SessionStore(window.localStorage, `countershade:${study.set.sha256}:${subject}:${session}`, study.post_url);
    this.store.headers = study.post_headers ?? {};
    this.store.flush(); // rows a reload left unsent
    this.resumed = this.store.rows.length > 0;
    if (this.resumed) this.procedure.resume(this.store.answered());
    this.ignoredRepeats = 0;
    // A 16-bit study draws its images through the app's dither (main.js has checked for WebGL2).
    if (study.bits === 16) this.deep = new DeepImages(engine, root, sessionSeed(engine, study.seed, subject, session));
    if (observer != null) this.observer = new SimulatedObserver(engine, observer, this.procedure);
    this.build(root);
  }

  build(root) {
    const { page, ink } = Object.assign(this, buildPage(root, this.study, 2));
    this.bar = element("div", { position: "absolute", left: "30%", width: "40%", top: "55%", height: "10px", border: `1px solid ${ink}`, display: "none" }, page);
    this.fill = element("div", { height: "100%", width: "0%", background: ink }, this.bar);
  }

  // Decodes one condition's images (once); shows a progress bar while the session waits for them.
  loadCondition(condition) {
    if (!this.loading.has(condition)) {
      const c = this.study.conditions[condition];
      const files = [c.reference, ...c.images];
      const started = performance.now();
      let done = 0;
      this.loading.set(condition, Promise.all(files.map(async (file) => {
        this.decoded.set(file, await decodeImage(file, c, this.deep));
        this.progress = { condition, done: ++done, total: files.length };
      })).then(() => {
        this.loaded.add(condition);
        this.loadSeconds[condition] = (performance.now() - started) / 1000; // for bench/web
      }));
    }
    return this.loading.get(condition);
  }

  // The conditions in the order the plan needs them from the current trial on, each loaded in turn
  // in the background, so the next trial's images are usually ready before it starts.
  async loadAhead() {
    const order = [...new Set(this.plan.slice(this.procedure.trial).map((t) => t.condition))];
    for (const c of order) await this.loadCondition(c);
  }

  ready() {
    return this.loaded.has(this.procedure.currentTrial.condition);
  }

  keyDown(e) {
    const key = KEYS[e.key];
    if (!key) return;
    e.preventDefault();
    if (e.repeat) return void ++this.ignoredRepeats; // the browser's repeat: the procedure times its own
    if (this.procedure.phase === "question" && !this.ready()) return; // a λ step never waits for an image
    this.press(key, this.now());
  }

  press(key, now) {
    const finished = this.procedure.phase === "finished";
    const answer = this.procedure.press(key, now);
    if (answer) this.record(answer);
    if (finished && (key === "enter" || key === "escape")) this.end("completed");
    if (this.procedure.phase === "quit") this.end("quit");
  }

  record(answer) {
    const trial = this.plan[answer.trialIndex];
    if (trial.practice) return;
    const c = this.study.conditions[trial.condition];
    this.store.add({
      subject: this.subject, scene: c.scene, sigma: c.sigma, question: answer.question, lambda: c.grid[answer.lambdaIndex],
      method: c.method, lambda_step: this.study.lambda_step, lambda_index: answer.lambdaIndex, lambda_max: c.lambda_max,
      start_index: answer.startIndex, repetition: trial.repetition, session: this.session, trial: trial.number, side: trial.side,
      n_keypresses: answer.keypresses, rt_ms: (answer.rt * 1000).toFixed(1), revision: answer.revision,
      timestamp_utc: new Date().toISOString(), stimulus_set: this.study.set.sha256, app_version: this.study.app_version, sequence: "",
      ...browserFields(this.environment, this.study.bits),
      plan_index: answer.trialIndex, question_index: QUESTIONS.indexOf(answer.question),
    });
  }

  now() {
    return (performance.now() - this.t0) / 1000;
  }

  showImages(place, files) {
    placeImages(this.images, place, files ?? [], this.decoded, this.deep);
  }

  draw() {
    const p = this.procedure, texts = this.study.texts;
    const messages = { instructions: this.resumed ? texts.resume : texts.welcome, practice_done: texts.practice_done,
                       paused: texts.paused, finished: texts.finished, quit: "" };
    if (p.phase !== "question") {
      this.showImages(null);
      this.bar.style.display = "none";
      [this.header, this.question, this.hint].forEach((e) => (e.textContent = ""));
      this.message.textContent = messages[p.phase];
      return;
    }
    const trial = p.currentTrial, c = this.study.conditions[trial.condition];
    if (!this.ready()) {
      this.loadCondition(trial.condition);
      this.showImages(null);
      const { done, total } = this.progress?.condition === trial.condition ? this.progress : { done: 0, total: 1 + c.images.length };
      this.bar.style.display = "block";
      this.fill.style.width = `${(100 * done) / total}%`;
      this.message.textContent = `Loading the stimuli: ${done} of ${total}`;
      return;
    }
    this.bar.style.display = "none";
    const place = layout(this.study, c, window.innerWidth, window.innerHeight, window.devicePixelRatio);
    if (!place) {
      this.showImages(null);
      this.message.textContent = "The window is too small to show the images at their true size. Please enlarge it, or set the browser's zoom to 100 %.";
      return;
    }
    const enhanced = c.images[p.index];
    this.showImages(place, trial.side === "left" ? [enhanced, c.reference] : [c.reference, enhanced]);
    this.message.textContent = "";
    const top = place.y / place.dpr, line = this.study.font_px * 1.35;
    this.header.style.top = `${top - 3.2 * line}px`;
    this.question.style.top = `${top - 1.9 * line}px`;
    this.hint.style.top = `${top + place.height / place.dpr + 0.8 * line}px`;
    this.header.textContent = trial.practice ? texts.practice : `Trial ${trial.number} of ${p.realTrialCount}`;
    this.question.textContent = texts.questions[p.question];
    this.hint.textContent = texts.keys_hint;
    window.countershadeShown = { trial: trial.number, question: p.question, lambda_index: p.index, side: trial.side,
                                 left: { x: place.left, y: place.y, file: trial.side === "left" ? enhanced : c.reference },
                                 right: { x: place.right, y: place.y, file: trial.side === "left" ? c.reference : enhanced } };
  }

  frame() {
    if (this.ended) return;
    const waiting = this.procedure.phase === "question" && !this.ready();
    const key = waiting ? null : this.observer?.act(this.now());
    if (key) this.press(key, this.now());
    if (this.observer && this.procedure.phase === "finished") this.end("completed"); // as the app's automated runs end
    if (this.ended) return;
    this.procedure.tick(this.now());
    this.draw();
    this.deep?.drawNext();
    requestAnimationFrame(() => this.frame());
  }

  start() {
    return new Promise((resolve) => {
      this.resolve = resolve;
      this.decoded = new Map();
      this.loading = new Map();
      this.loaded = new Set();
      this.loadSeconds = {};
      this.loadAhead().catch((error) => (this.message.textContent = `A stimulus could not be loaded: ${error.message}`));
      this.t0 = performance.now();
      this.onKeyDown = (e) => this.keyDown(e);
      this.onKeyUp = (e) => KEYS[e.key] && this.procedure.release(KEYS[e.key], this.now());
      document.addEventListener("keydown", this.onKeyDown);
      document.addEventListener("keyup", this.onKeyUp);
      this.frame();
    });
  }

  end(how) {
    this.ended = true;
    document.removeEventListener("keydown", this.onKeyDown);
    document.removeEventListener("keyup", this.onKeyUp);
    const result = { end: how, answers: this.store.rows.length, csv: this.store.csv(), browser_repeats_ignored: this.ignoredRepeats };
    window.countershadeResult = result;
    this.resolve(result);
  }
}

export const CountershadeAdjustPlugin = sessionPlugin("countershade-adjust", (page, engine, t) =>
  new AdjustSession(page, engine, t.study, t.subject, t.session, t.environment, t.observer));
