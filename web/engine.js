// The page's link to the study logic. The plan, the procedure and the simulated observer are the
// app's C++ compiled to WebAssembly (countershade-engine.js and .wasm beside index.html, built from
// src/web_engine); this file only loads that engine and gives its objects the shape the plugin
// draws from. No study logic lives here, so the browser cannot drift from the app.

export const QUESTIONS = ["low", "high", "best"];

// Starts the engine. In a page, countershade-engine.js defines the factory and fetches the .wasm
// beside it; Node.js passes the factory and the .wasm's bytes ({ wasmBinary }).
export function loadEngine(factory = globalThis.CountershadeEngine, options = {}) {
  if (typeof factory !== "function") throw new Error("countershade-engine.js is not loaded");
  return factory(options);
}

// The seed of a subject's session (decimal text: it has 64 bits).
export function sessionSeed(engine, studySeed, subject, session) {
  return engine.sessionSeed(String(studySeed), subject, session);
}

// The app's plan for a subject's session: practice trials first, then every condition ×
// repetition in the seeded order; each {number, practice, condition, repetition, side, start}.
export function planSession(engine, study, subject, session) {
  return JSON.parse(engine.planSession(JSON.stringify(study), subject, session));
}

// The method-of-adjustment procedure (src/adjust/procedure.cpp) over a plan. Keys by name (up,
// down, left, right, enter, backspace, escape, q), times in seconds.
export class AdjustmentProcedure {
  constructor(engine, study, plan) {
    this.plan = plan;
    this.native = new engine.AdjustmentProcedure(JSON.stringify(study), JSON.stringify(plan));
  }

  get phase() { return this.native.phase(); }
  get done() { return this.native.done(); }
  get trial() { return this.native.trialIndex(); }
  get currentTrial() { return this.plan[this.trial]; }
  get question() { return this.native.question(); }
  get index() { return this.native.lambdaIndex(); }
  get realTrialCount() { return this.native.realTrialCount(); }

  // A key press; the answer it confirmed ({trialIndex, question, lambdaIndex, startIndex,
  // keypresses, rt, revision}), if any.
  press(key, time) {
    const answer = this.native.press(key, time);
    return answer ? JSON.parse(answer) : undefined;
  }
  release(key, time) { this.native.release(key, time); }
  tick(time) { this.native.tick(time); }

  // Continues from stored answers: a Map "planIndex,question" → {lambdaIndex, revision}.
  resume(answered) {
    const rows = [...answered].map(([key, a]) => [...key.split(",").map(Number), a.lambdaIndex, a.revision]);
    this.native.resume(JSON.stringify(rows));
  }
}

// The app's simulated observer (--observer simulated:SEED, or model:SEED from the page's
// prediction) watching a procedure: act() gives the key it presses now, or null. A bare number is
// simulated:NUMBER.
export class SimulatedObserver {
  constructor(engine, spec, procedure) {
    const full = /^\d+$/.test(String(spec)) ? `simulated:${spec}` : String(spec);
    this.native = new engine.AdjustmentObserver(full, procedure.native);
  }

  act(time) {
    return this.native.key(time) || null;
  }
}

// The trials CSV's columns of a forced-choice session, in order, as the app writes them.
export function choiceColumns(engine) {
  return JSON.parse(engine.choiceColumns());
}

// A forced-choice session (src/forced_choice/choice_run.cpp with the procedure plug-ins): the
// trial to show, its answer and the app's row for it, and a replay of stored rows after a reload.
export class ChoiceSession {
  constructor(engine, study, subject, session) {
    this.native = new engine.ChoiceSession(JSON.stringify(study), subject, session);
  }

  // {number, practice, condition, condition_trial, requested, lambda_index, lambda, target}, or
  // null once the session is finished.
  get current() { return JSON.parse(this.native.current()); }
  get finished() { return this.native.finished(); }
  get inPractice() { return this.native.inPractice(); }

  // Answers the current trial: {correct, row} with the row's fields (empty for practice).
  answer(response, rtSeconds, timeUtc) {
    return JSON.parse(this.native.answerWithRow(response, rtSeconds, timeUtc));
  }
  // The row of an answer that does not count (the trial stays, to be shown again).
  rowWithoutAnswer(response, rtSeconds, timeUtc) {
    return JSON.parse(this.native.rowWithoutAnswer(response, rtSeconds, timeUtc));
  }
  // Rebuilds the session from its stored rows (arrays of fields), as the app's resume does.
  replay(rows) { this.native.replay(JSON.stringify(rows)); }
}

// The app's simulated forced-choice observer (--observer weibull:ALPHA,BETA,SEED, or model:SEED
// from the page's prediction) in a session.
export class ChoiceObserver {
  constructor(engine, spec, session) {
    this.native = new engine.ChoiceObserver(spec, session.native);
  }

  get delay() { return this.native.delay(); }
  respond(trial, practiceIndex, nAfc) {
    return this.native.respondTo(trial.condition, trial.number, practiceIndex, trial.lambda, trial.target, nAfc);
  }
}
