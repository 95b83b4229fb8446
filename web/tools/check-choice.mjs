// Checks the page's forced-choice engine (WebAssembly) against the app: reads the sessions a test
// ran natively (tests/web/choice_engine_test.cpp), runs each again in the engine with the same
// simulated observer, and exits 1 naming the first trial or state that differs.
//   node web/tools/check-choice.mjs CASES.json

import { readFileSync } from "node:fs";
import { isDeepStrictEqual } from "node:util";

import { nodeEngine } from "./node-engine.mjs";

function runSession(engine, c) {
  const session = new engine.ChoiceSession(JSON.stringify(c.page), c.subject, c.session);
  const observer = new engine.ChoiceObserver(c.observer);
  const nAfc = c.page.forced_choice.n_afc ?? 2;
  const trials = [];
  for (let practiceIndex = 0, t; (t = JSON.parse(session.current())); ) {
    const response = observer.respond(t.number, practiceIndex, t.lambda, t.target, nAfc);
    const correct = session.answer(response);
    practiceIndex += t.practice ? 1 : 0;
    trials.push([t.number, t.practice, t.condition, t.condition_trial, t.requested, t.lambda_index, t.lambda, t.target, response, correct]);
  }
  const states = JSON.parse(session.conditions()).map((c) => JSON.parse(session.procedureState(c)));
  return { seed: session.sessionSeed(), trials, states };
}

const engine = await nodeEngine();
const cases = JSON.parse(readFileSync(process.argv[2], "utf8"));
let trials = 0;
for (const [n, c] of cases.entries()) {
  const browser = runSession(engine, c);
  if (browser.seed !== c.app.seed) {
    console.log(`session ${n}: seed ${browser.seed} where the app has ${c.app.seed}`);
    process.exit(1);
  }
  const rows = Math.max(browser.trials.length, c.app.trials.length);
  for (let i = 0; i < rows; ++i)
    if (!isDeepStrictEqual(browser.trials[i], c.app.trials[i])) {
      console.log(`session ${n} (${c.page.forced_choice.procedure.type}) trial ${i}: browser ${JSON.stringify(browser.trials[i])}, app ${JSON.stringify(c.app.trials[i])}`);
      process.exit(1);
    }
  if (!isDeepStrictEqual(browser.states, c.app.states)) {
    console.log(`session ${n} (${c.page.forced_choice.procedure.type}): final states differ\n browser ${JSON.stringify(browser.states)}\n app     ${JSON.stringify(c.app.states)}`);
    process.exit(1);
  }
  trials += rows;
}
console.log(`${cases.length} sessions, ${trials} trials: the same as the app's`);
