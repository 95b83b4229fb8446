// The browser's adjustment procedure without a browser: the app's key repeat (400 ms, then every
// 100 ms; the browser's own repeat is not used), Backspace, pause, and resume.

import { test } from "node:test";
import assert from "node:assert/strict";

import { Procedure } from "../procedure.js";

const plan = [
  { number: 0, practice: true, condition: 0, repetition: 1, side: "left", start: [2, 2, 2] },
  { number: 1, practice: false, condition: 1, repetition: 1, side: "right", start: [0, 3, 5] },
  { number: 2, practice: false, condition: 0, repetition: 1, side: "left", start: [1, 1, 1] },
];
const grid = [6, 11];

test("a held arrow steps once, then after 400 ms every 100 ms, and stops on release", () => {
  const p = new Procedure(grid, plan);
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
  const p = new Procedure(grid, plan);
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
  const p = new Procedure(grid, plan);
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
  const p = new Procedure(grid, plan);
  p.resume(new Map([["1,0", { lambdaIndex: 4, revision: 0 }], ["1,1", { lambdaIndex: 6, revision: 0 }]]));
  p.press("enter", 0);
  assert.deepEqual([p.currentTrial.number, p.question, p.index], [1, 2, 5]);
  p.press("backspace", 1);
  assert.equal(p.index, 6);
});
