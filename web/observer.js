// The app's simulated observer (src/adjust/input_script.cpp), so a browser session can be run
// without a person and compared with the app's, row for row: for each condition, latent
// thresholds drawn from the seed; it answers with the first grid value at or above them, stepping
// there with one key press every 20 ms.

import { SampleStream, hashString } from "./random.js";

// A standard normal deviate from two uniforms (Box–Muller), as the app draws it.
function normal(stream) {
  const u1 = Math.max(stream.next(), 1e-300), u2 = stream.next();
  return Math.sqrt(-2 * Math.log(u1)) * Math.cos(2 * Math.PI * u2);
}

export class SimulatedObserver {
  constructor(seed, conditions, interval = 0.02) {
    this.seed = BigInt(seed);
    this.conditions = conditions;
    this.interval = interval;
    this.nextAction = 0;
  }

  latentLambda(condition, repetition, question) {
    const c = this.conditions[condition];
    const top = c.grid_values[c.grid_values.length - 1];
    const key = hashString(`${c.scene}/${c.method}`);
    const sigma = BigInt(Math.trunc(c.sigma_value * 1e9));
    const person = new SampleStream(this.seed, key, sigma, 0n);
    const low = 0.2 * top * Math.exp(0.2 * normal(person));
    const ratio = [1.0, 3.0 * Math.exp(0.1 * normal(person)), 1.6 * Math.exp(0.1 * normal(person))];
    const noise = new SampleStream(this.seed, key, sigma, BigInt(repetition) * 8n + BigInt(question) + 1n);
    return low * ratio[question] * Math.exp(0.05 * normal(noise));
  }

  answerIndex(condition, repetition, question) {
    const grid = this.conditions[condition].grid_values;
    const latent = this.latentLambda(condition, repetition, question);
    const i = grid.findIndex((lambda) => lambda >= latent - 1e-12);
    return i < 0 ? grid.length - 1 : i;
  }

  // The key to press now, if any.
  act(procedure, time) {
    if (time < this.nextAction || procedure.done) return null;
    this.nextAction = time + this.interval;
    if (procedure.phase === "paused") return "escape";
    if (procedure.phase !== "question") return "enter";
    const t = procedure.currentTrial;
    const target = this.answerIndex(t.condition, t.repetition, procedure.question);
    return procedure.index < target ? "right" : procedure.index > target ? "left" : "enter";
  }
}
