// Goes through an exported study's virtual chinrest in Debian's headless Chromium as a participant
// would: drags the card's corner by DRAG_PX, presses Space five times to start the ball and
// BALL_MS later to stop it, confirms the distance, reloads the page once during the session (the
// measurement must not be asked for again), and lets the simulated observer finish. Prints, as
// JSON, what the page measured and recorded:
//   node web/tools/browser-chinrest.mjs STUDY_DIR SEED OUT.csv
// {card_px, square_x, ball_x: [...], asked_again, transform}; the session's CSV goes to OUT.csv.

import { writeFile } from "node:fs/promises";

import puppeteer from "puppeteer-core";

import { serve } from "./static-server.mjs";

const [dir, seed, out] = process.argv.slice(2);
const DRAG_PX = 40, BALL_MS = 400;
const server = await serve(dir);
const browser = await puppeteer.launch({ executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium-headless-shell",
                                         args: ["--no-sandbox", "--force-color-profile=srgb"] });
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const centre = async (page, selector) => page.$eval(selector, (e) => {
  const b = e.getBoundingClientRect();
  return { x: b.left + b.width / 2, y: b.top + b.height / 2, width: b.width };
});

// The card: press on the resize handle, move right, release; then "the image is the right size".
async function resizeCard(page) {
  const handle = await page.waitForSelector("#jspsych-resize-handle");
  const h = await centre(page, "#jspsych-resize-handle");
  await page.mouse.move(h.x, h.y);
  await page.mouse.down();
  await page.mouse.move(h.x + DRAG_PX / 2, h.y, { steps: 4 });
  await page.mouse.move(h.x + DRAG_PX, h.y, { steps: 4 });
  await page.mouse.up();
  const card = (await centre(page, "#item")).width;
  await handle.dispose();
  await page.click("#end_resize_phase");
  return card;
}

// Five blind-spot runs: Space starts the ball, Space BALL_MS later stops it. A listener that runs
// before the page's notes the ball's centre at each stop, where the chinrest reads it.
async function blindSpot(page) {
  await page.waitForSelector("#virtual-chinrest-circle");
  const square = (await centre(page, "#virtual-chinrest-square")).x;
  await page.evaluate(() => {
    window.ballAtSpace = [];
    window.addEventListener("keydown", (e) => {
      const ball = document.querySelector("#virtual-chinrest-circle");
      if (e.key === " " && ball) {
        const b = ball.getBoundingClientRect();
        window.ballAtSpace.push(b.left + b.width / 2);
      }
    }, true);
  });
  for (let rep = 0; rep < 5; ++rep) {
    await page.keyboard.press("Space");
    await sleep(BALL_MS);
    await page.keyboard.press("Space");
    await sleep(100);
  }
  const balls = (await page.evaluate(() => window.ballAtSpace)).filter((_, i) => i % 2 === 1);
  await page.waitForSelector("#distance-estimate");
  await page.click("#distance-report #proceed");
  return { square, balls };
}

try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1200, height: 800, deviceScaleFactor: 1 });
  await page.goto(`http://127.0.0.1:${server.address().port}/?subject=P05&observer=simulated:${seed}`);
  const card = await resizeCard(page);
  const { square, balls } = await blindSpot(page);
  await page.waitForFunction(() => (window.countershadeSession?.store.rows.length ?? 0) >= 1, { timeout: 120000, polling: 5 });
  await page.reload();
  const askedAgain = await Promise.race([
    page.waitForSelector("#jspsych-resize-handle", { timeout: 0 }).then(() => true),
    page.waitForFunction(() => window.countershadeSession?.t0 !== undefined, { timeout: 120000 }).then(() => false),
  ]);
  await page.waitForFunction(() => window.countershadeResult, { timeout: 300000 });
  await writeFile(out, await page.evaluate(() => window.countershadeResult.csv));
  const transform = await page.$eval("#jspsych-content", (e) => e.style.transform);
  console.log(JSON.stringify({ card_px: card, square_x: square, ball_x: balls, asked_again: askedAgain, transform }));
} finally {
  await browser.close();
  server.close();
}
