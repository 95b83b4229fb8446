// The method-of-adjustment procedure as a plain state machine, the same as the app's
// (src/adjust/procedure.cpp, docs/adjustment-study.md): three questions per trial, arrows step the
// λ grid index, a held arrow repeats after 400 ms every 100 ms (the browser's own key repeat is
// ignored), Enter confirms, Backspace returns to the previous question, Esc pauses. It knows no
// page: the plugin feeds it key events with their times and draws what it says.

export const QUESTIONS = ["low", "high", "best"];
const STEP_KEYS = { up: +1, right: +1, down: -1, left: -1 };

export class Procedure {
  constructor(gridSizes, plan, timing = { delay: 0.4, interval: 0.1 }) {
    this.gridSizes = gridSizes;
    this.plan = plan;
    this.timing = timing;
    this.phase = "instructions";
    this.pausedFrom = "instructions";
    this.trial = 0;
    this.question = 0;
    this.index = plan[0].start[0];
    this.keypresses = 0;
    this.shownAt = 0;
    this.pausedAt = 0;
    this.held = null;
    this.nextRepeat = 0;
    this.answered = new Map(); // "trial,question" → {lambdaIndex, revision}, real trials only
    this.practiceAnswers = new Map();
  }

  get realTrialCount() {
    return this.plan.filter((t) => !t.practice).length;
  }
  get currentTrial() {
    return this.plan[this.trial];
  }
  get done() {
    return this.phase === "finished" || this.phase === "quit";
  }

  // Continue a session: skip practice and every answered question; start at the first unanswered.
  resume(answered) {
    this.answered = new Map(answered);
    this.phase = "finished";
    for (let t = 0; t < this.plan.length; ++t) {
      if (this.plan[t].practice) continue;
      for (let q = 0; q < 3; ++q)
        if (!this.answered.has(`${t},${q}`)) {
          this.trial = t;
          this.question = q;
          this.phase = "instructions";
          return;
        }
    }
  }

  enterQuestion(trial, question, time) {
    this.trial = trial;
    this.question = question;
    const t = this.plan[trial];
    const past = (t.practice ? this.practiceAnswers : this.answered).get(`${trial},${question}`);
    const index = past ? past.lambdaIndex : t.start[question];
    this.index = Math.min(Math.max(index, 0), this.gridSizes[t.condition] - 1);
    this.keypresses = 0;
    this.shownAt = time;
    this.held = null;
    this.phase = "question";
  }

  step(direction) {
    this.index = Math.min(Math.max(this.index + direction, 0), this.gridSizes[this.currentTrial.condition] - 1);
  }

  advance(time) {
    if (this.question + 1 < 3) return this.enterQuestion(this.trial, this.question + 1, time);
    const next = this.trial + 1;
    this.held = null;
    if (next >= this.plan.length) {
      this.phase = "finished";
    } else if (this.plan[this.trial].practice && !this.plan[next].practice) {
      this.trial = next;
      this.question = 0;
      this.phase = "practice_done";
    } else {
      this.enterQuestion(next, 0, time);
    }
  }

  pressBetweenQuestions(key, time) {
    if (this.phase === "instructions" || this.phase === "practice_done") {
      if (key === "enter") this.enterQuestion(this.trial, this.question, time);
      else if (key === "escape") [this.pausedFrom, this.phase] = [this.phase, "paused"];
    } else if (this.phase === "paused") {
      if (key === "enter" || key === "escape") {
        this.phase = this.pausedFrom;
        if (this.phase === "question") this.shownAt += time - this.pausedAt; // a pause is no response time
      } else if (key === "q") {
        this.phase = "quit";
      }
    }
  }

  confirm(time) {
    const t = this.currentTrial;
    const past = t.practice ? this.practiceAnswers : this.answered;
    const key = `${this.trial},${this.question}`;
    const before = past.get(key);
    const answer = {
      trialIndex: this.trial,
      question: QUESTIONS[this.question],
      lambdaIndex: this.index,
      startIndex: t.start[this.question],
      keypresses: this.keypresses,
      rt: time - this.shownAt,
      revision: before ? before.revision + 1 : 0,
    };
    past.set(key, { lambdaIndex: this.index, revision: answer.revision });
    this.advance(time);
    return answer;
  }

  // A key press; returns the answer when the key confirmed one.
  press(key, time) {
    if (this.phase !== "question") return void this.pressBetweenQuestions(key, time);
    if (key in STEP_KEYS) {
      this.step(STEP_KEYS[key]);
      ++this.keypresses;
      this.held = key;
      this.nextRepeat = time + this.timing.delay;
    } else if (key === "enter") {
      return this.confirm(time);
    } else if (key === "backspace") {
      if (this.question > 0) this.enterQuestion(this.trial, this.question - 1, time);
    } else if (key === "escape") {
      this.held = null;
      this.pausedFrom = "question";
      this.phase = "paused";
      this.pausedAt = time;
    }
    return undefined;
  }

  release(key, time) {
    if (this.held === key) {
      this.tick(time); // the repeats that fell due while the key was still down
      this.held = null;
    }
  }

  tick(time) {
    if (this.phase !== "question" || !this.held) return;
    while (time >= this.nextRepeat) {
      this.step(STEP_KEYS[this.held]);
      this.nextRepeat += this.timing.interval;
    }
  }
}
