// Checks the page's forced-choice engine (WebAssembly) against the app: reads the sessions a test
// ran natively (tests/web/choice_engine_test.cpp) and runs each again in the engine with the same
// simulated observer: every trial, every CSV row and the final states must be the app's. Each is
// run twice, the second time rebuilt from its rows half-way, as after a reload. Exits 1 naming the
// first difference.
//   node web/tools/check-choice.mjs CASES.json

import { readFileSync } from "node:fs";
import { isDeepStrictEqual } from "node:util";

import { nodeEngine } from "./node-engine.mjs";

// The session, answered by the observer; with `reloadAfter`, a new session replays the rows
// recorded so far after that many real trials and goes on in its place.
function runSession(engine, c, reloadAfter = null) {
  let session = new engine.ChoiceSession(JSON.stringify(c.page), c.subject, c.session);
  const observer = new engine.ChoiceObserver(c.observer, session);
  const nAfc = c.page.forced_choice.n_afc ?? 2;
  const trials = [], rows = [];
  for (let practiceIndex = 0, t; (t = JSON.parse(session.current())); ) {
    const response = observer.respondTo(t.condition, t.number, practiceIndex, t.lambda, t.target, nAfc);
    const { correct, row } = JSON.parse(session.answerWithRow(response, 0.5 + 0.001 * t.number, "T"));
    practiceIndex += t.practice ? 1 : 0;
    trials.push([t.number, t.practice, t.condition, t.condition_trial, t.requested, t.lambda_index, t.lambda, t.target, response, correct]);
    if (!t.practice) rows.push(row);
    if (rows.length === reloadAfter && !t.practice) {
      session = new engine.ChoiceSession(JSON.stringify(c.page), c.subject, c.session);
      session.replay(JSON.stringify(rows));
    }
  }
  const states = JSON.parse(session.conditions()).map((k) => JSON.parse(session.procedureState(k)));
  return { seed: session.sessionSeed(), trials, rows, states };
}

function firstDifference(browser, app) {
  if (browser.seed !== app.seed) return `seed ${browser.seed} where the app has ${app.seed}`;
  for (const part of ["trials", "rows"])
    for (let i = 0; i < Math.max(browser[part].length, app[part].length); ++i)
      if (!isDeepStrictEqual(browser[part][i], app[part][i]))
        return `${part} ${i}: browser ${JSON.stringify(browser[part][i])}, app ${JSON.stringify(app[part][i])}`;
  if (!isDeepStrictEqual(browser.states, app.states))
    return `final states differ\n browser ${JSON.stringify(browser.states)}\n app     ${JSON.stringify(app.states)}`;
  return null;
}

const engine = await nodeEngine();
const cases = JSON.parse(readFileSync(process.argv[2], "utf8"));
let trials = 0;
for (const [n, c] of cases.entries()) {
  for (const reloadAfter of [null, Math.floor(c.app.rows.length / 2)]) {
    const difference = firstDifference(runSession(engine, c, reloadAfter), c.app);
    if (difference) {
      console.log(`session ${n} (${c.page.forced_choice.procedure.type}${reloadAfter ? `, reloaded after ${reloadAfter} rows` : ""}): ${difference}`);
      process.exit(1);
    }
  }
  trials += c.app.trials.length;
}
console.log(`${cases.length} sessions, ${trials} trials, each also reloaded half-way: the same as the app's`);
