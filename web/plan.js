// The trial plan of an adjustment session, as src/adjust/procedure.cpp makes it: practice trials
// first, then every condition × repetition in a seeded order, sides counterbalanced, start indices
// seeded. The same study and seed give the app's plan, row for row.

import { SampleStream, hashCombine, hashString } from "./random.js";

const STREAM = { order: 101n, side: 102n, start: 103n, practice: 104n };

export function seededShuffle(items, seed, stream) {
  const random = new SampleStream(seed, stream, 0n, 0n);
  for (let i = items.length; i > 1; --i) {
    const j = Math.min(Math.floor(random.next() * i), i - 1);
    [items[i - 1], items[j]] = [items[j], items[i - 1]];
  }
  return items;
}

// The seed of one subject's session: the study seed mixed with the subject id and session number.
export function sessionSeed(studySeed, subject, session) {
  return hashCombine(hashCombine(BigInt(studySeed), hashString(subject)), BigInt(session));
}

function drawStart(gridSize, settings, trialKey, question) {
  if (settings.start === "zero") return 0;
  const random = new SampleStream(settings.seed, STREAM.start, BigInt(trialKey), BigInt(question));
  return Math.min(Math.floor(random.next() * gridSize), gridSize - 1);
}

function realTrials(n, settings) {
  const firstSide = seededShuffle(Array.from({ length: n }, (_, c) => (c % 2 === 0 ? "left" : "right")), settings.seed, STREAM.side);
  const real = [];
  for (let r = 1; r <= settings.repetitions; ++r)
    for (let c = 0; c < n; ++c) {
      const flip = (r - 1) % 2 === 1;
      const side = settings.side !== "counterbalanced" ? settings.side : (firstSide[c] === "left") !== flip ? "left" : "right";
      real.push({ condition: c, repetition: r, side });
    }
  return seededShuffle(real, settings.seed, STREAM.order);
}

function practiceTrials(gridSizes, settings) {
  const pool = settings.practiceConditions.length ? [...settings.practiceConditions] : gridSizes.map((_, c) => c);
  const pick = seededShuffle(pool, settings.seed, STREAM.practice);
  const practice = [];
  for (let p = 0; p < settings.practiceTrials; ++p) {
    const condition = pick[p % pick.length];
    const side = settings.side === "counterbalanced" ? (p % 2 === 0 ? "left" : "right") : settings.side;
    const key = (1n << 40n) + BigInt(p);
    const start = [0, 1, 2].map((q) => drawStart(gridSizes[condition], settings, key, q));
    practice.push({ number: 0, practice: true, condition, repetition: 1, side, start });
  }
  return practice;
}

// gridSizes: per condition, its number of λ values. settings: {seed (BigInt), repetitions, side,
// start, practiceTrials, practiceConditions}.
export function planTrials(gridSizes, settings) {
  const plan = practiceTrials(gridSizes, settings);
  realTrials(gridSizes.length, settings).forEach((t, i) => {
    const start = [0, 1, 2].map((q) => drawStart(gridSizes[t.condition], settings, BigInt(i + 1), q));
    plan.push({ number: i + 1, practice: false, ...t, start });
  });
  return plan;
}
