// Checks the browser's plan against the app's: reads the cases a test wrote (the app's plans from
// src/adjust/procedure.cpp, built natively) and plans them again in the WebAssembly engine the
// page runs. Exits 1 naming the first row that differs.

import { readFileSync } from "node:fs";

import { planSession, sessionSeed } from "../engine.js";
import { nodeEngine } from "./node-engine.mjs";

// A study as the page has it, with just what the plan reads.
function studyOf(c) {
  return {
    seed: c.study_seed, repetitions: c.repetitions, side: c.side, start: c.start,
    practice_trials: c.practice_trials, practice_conditions: c.practice_conditions,
    lambda_grid: { min: 0, step: 0.05 },
    conditions: c.grid_sizes.map((n) => ({ scene: "scene", method: "method", sigma_value: 0.1, grid: Array(n).fill("") })),
  };
}

const engine = await nodeEngine();
const cases = JSON.parse(readFileSync(process.argv[2], "utf8"));
let rows = 0;
for (const [n, c] of cases.entries()) {
  const seed = sessionSeed(engine, c.study_seed, c.subject, c.session);
  if (seed !== c.session_seed) {
    console.log(`case ${n}: session seed ${seed} where the app has ${c.session_seed}`);
    process.exit(1);
  }
  const plan = planSession(engine, studyOf(c), c.subject, c.session);
  if (plan.length !== c.plan.length) {
    console.log(`case ${n}: ${plan.length} trials where the app has ${c.plan.length}`);
    process.exit(1);
  }
  for (const [i, t] of plan.entries()) {
    const a = c.plan[i];
    const same = t.number === a.number && t.practice === a.practice && t.condition === a.condition &&
                 t.repetition === a.repetition && t.side === a.side && t.start.join() === a.start.join();
    if (!same) {
      console.log(`case ${n} row ${i}: browser ${JSON.stringify(t)}, app ${JSON.stringify(a)}`);
      process.exit(1);
    }
    ++rows;
  }
}
console.log(`${cases.length} plans, ${rows} rows: the same as the app's`);
