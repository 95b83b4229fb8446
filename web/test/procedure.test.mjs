// The browser's adjustment procedure without a browser, through the WebAssembly engine the page
// loads: the app's key repeat (400 ms, then every 100 ms; the browser's own repeat is not used),
// Backspace, pause, and resume, as engine.js hands them to the plugin.

import { test } from "node:test";
import assert from "node:assert/strict";

import { AdjustmentProcedure, SimulatedObserver } from "../engine.js";
import { nodeEngine } from "../tools/node-engine.mjs";

const engine = await nodeEngine();

const plan = [
  { number: 0, practice: true, condition: 0, repetition: 1, side: "left", start: [2, 2, 2] },
  { number: 1, practice: false, condition: 1, repetition: 1, side: "right", start: [0, 3, 5] },
  { number: 2, practice: false, condition: 0, repetition: 1, side: "left", start: [1, 1, 1] },
];
const study = {
  timing: { delay: 0.4, interval: 0.1 },
  lambda_grid: { min: 0, step: 0.05 },
  conditions: [6, 11].map((n, c) => ({ scene: `scene${c}`, method: "usm2d", sigma_value: 0.1, grid: Array(n).fill("") })),
};

test("a held arrow steps once, then after 400 ms every 100 ms, and stops on release", () => {
  const p = new AdjustmentProcedure(engine, study, plan);
  p.press("enter", 0);
  assert.equal(p.phase, "question");
  p.press("up", 1.0);
  assert.equal(p.index, 3);
  p.tick(1.39);
  assert.equal(p.index, 3);
  p.tick(1.4);
  assert.equal(p.index, 4);
  p.tick(1.5);
  assert.equal(p.index, 5);
  p.tick(1.75);
  assert.equal(p.index, 5, "clamped at the top of the grid");
  p.release("up", 1.8);
  p.tick(3);
  assert.equal(p.index, 5);
});

test("Enter answers, Backspace returns with the answer and raises its revision", () => {
  const p = new AdjustmentProcedure(engine, study, plan);
  p.press("enter", 0);
  ["enter", "enter", "enter"].forEach((k, i) => p.press(k, i + 1)); // the practice trial's three answers
  assert.equal(p.phase, "practice_done");
  p.press("enter", 5);
  assert.equal(p.currentTrial.number, 1);
  p.press("right", 5.1);
  const low = p.press("enter", 6);
  assert.deepEqual([low.question, low.lambdaIndex, low.startIndex, low.keypresses, low.revision], ["low", 1, 0, 1, 0]);
  assert.ok(Math.abs(low.rt - 1) < 1e-12);
  p.press("backspace", 7);
  assert.equal(p.question, 0);
  assert.equal(p.index, 1, "the recorded answer");
  assert.equal(p.press("enter", 8).revision, 1);
});

test("a pause does not count towards the response time, and q quits from it", () => {
  const p = new AdjustmentProcedure(engine, study, plan);
  p.resume(new Map());
  assert.equal(p.currentTrial.number, 1, "a resume skips practice");
  p.press("enter", 0);
  p.press("escape", 1);
  assert.equal(p.phase, "paused");
  p.press("enter", 11);
  assert.ok(Math.abs(p.press("enter", 12).rt - 2) < 1e-12);
  p.press("escape", 13);
  p.press("q", 14);
  assert.equal(p.phase, "quit");
});

test("a resume starts at the first unanswered question", () => {
  const p = new AdjustmentProcedure(engine, study, plan);
  p.resume(new Map([["1,0", { lambdaIndex: 4, revision: 0 }], ["1,1", { lambdaIndex: 6, revision: 0 }]]));
  p.press("enter", 0);
  assert.deepEqual([p.currentTrial.number, p.question, p.index], [1, 2, 5]);
  p.press("backspace", 1);
  assert.equal(p.index, 6);
});

test("the simulated observer answers every real question, and the answers stay on the grid", () => {
  const p = new AdjustmentProcedure(engine, study, plan);
  const observer = new SimulatedObserver(engine, 7, p);
  const answers = [];
  for (let time = 0; !p.done && time < 60; time += 0.01) {
    const key = observer.act(time);
    if (!key) continue;
    const answer = p.press(key, time);
    p.release(key, time);
    if (answer && !plan[answer.trialIndex].practice) answers.push(answer);
  }
  assert.equal(p.phase, "finished");
  assert.deepEqual(answers.map((a) => [a.trialIndex, a.question]), [[1, "low"], [1, "high"], [1, "best"], [2, "low"], [2, "high"], [2, "best"]]);
  for (const a of answers) assert.ok(a.lambdaIndex >= 0 && a.lambdaIndex < study.conditions[plan[a.trialIndex].condition].grid.length);
});

test("a study the engine cannot read is an Error naming the field", () => {
  assert.throws(() => new AdjustmentProcedure(engine, { conditions: [] }, plan), /lambda_grid/);
});
