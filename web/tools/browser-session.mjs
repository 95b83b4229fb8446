// Runs a whole session of an exported study in Debian's headless Chromium with the simulated
// observer, optionally reloading the page at given moments, and writes the CSV the page offers.
// The server also takes the study's POSTs to /collect, refusing the first two attempts at every
// row ($REFUSE to change that; REFUSE=all refuses every row and leaves them unsent; $REFUSE_STATUS
// is the refusal's HTTP status, 503 by default), and writes the
// rows it accepted, in order, to OUT.csv.posted. OUT.csv.end holds the page's last line as the
// session ends, and OUT.csv.end-sent that line once every row is sent.
//   node web/tools/browser-session.mjs STUDY_DIR SUBJECT OBSERVER OUT.csv [RELOAD_AFTER_ANSWERS...]
// STUDY_DIR may instead be the URL of a study that `countershade serve` hosts, with the
// participant's ?link=…; that server then takes the rows, SUBJECT is left to the link,
// OUT.csv.posted is not written, and OUT.csv.token holds the token the page claimed its session
// with (for tests that go on as that participant).
// OBSERVER: a number (the adjustment study's simulated:SEED), or a spec the page takes as it is
// (weibull:ALPHA,BETA,SEED for a forced-choice study).

import { writeFile } from "node:fs/promises";

import { launchChromium } from "./chromium.mjs";
import { serve } from "./static-server.mjs";

const [dir, subject, observer, out, ...reloads] = process.argv.slice(2);
const spec = /^\d+$/.test(observer) ? `simulated:${observer}` : observer;
const posted = [];
const hosted = /^https?:/.test(dir);
const refuseAll = process.env.REFUSE === "all";
const server = hosted ? null : await serve(dir, (row) => posted.push(row), refuseAll ? Infinity : Number(process.env.REFUSE ?? 2),
                                       Number(process.env.REFUSE_STATUS ?? 503));
const endLine = () => page.evaluate(() => document.getElementById("countershade-end")?.textContent ?? "");
let page;
const blocked = [];
const browser = await launchChromium();
try {
  page = await browser.newPage();
  // Anything the page's Content-Security-Policy blocks is an error of the page or the policy.
  page.on("console", (m) => { if (/Content Security Policy/.test(m.text())) blocked.push(m.text().slice(0, 120)); });
  await page.setViewport({ width: 900, height: 600, deviceScaleFactor: 1 });
  // $STALL=N: the page holds trial N's first interval once (a forced-choice timing fault).
  if (process.env.STALL) await page.evaluateOnNewDocument((n) => (window.countershadeStallTrial = n), Number(process.env.STALL));
  const url = hosted ? `${dir}&observer=${spec}`
                     : `http://127.0.0.1:${server.address().port}/?subject=${subject}&observer=${spec}`;
  await page.goto(url);
  // Reload after the given numbers of stored answers: the page must resume where it stopped.
  for (const after of reloads.map(Number)) {
    await page.waitForFunction((n) => (window.countershadeSession?.store.rows.length ?? 0) >= n || window.countershadeResult,
                               { timeout: 120000, polling: 5 }, after);
    await page.reload();
  }
  await page.waitForFunction(() => window.countershadeResult, { timeout: 300000 });
  await writeFile(out, await page.evaluate(() => window.countershadeResult.csv));
  await page.waitForFunction(() => document.getElementById("countershade-end"), { timeout: 60000, polling: 5 });
  await writeFile(`${out}.end`, await endLine());
  if (!refuseAll) {
    // Every row sent before the page is closed (the store retries each refused POST after a second).
    await page.waitForFunction(() => !window.countershadeSession?.store.postUrl ||
                               window.countershadeSession.store.posted === window.countershadeSession.store.rows.length,
                               { timeout: 300000, polling: 50 });
    if (!hosted) await writeFile(`${out}.posted`, posted.join("\n") + (posted.length ? "\n" : ""));
    await page.waitForFunction(() => /All answers are saved/.test(document.getElementById("countershade-end").textContent),
                               { timeout: 10000, polling: 50 });
    await writeFile(`${out}.end-sent`, await endLine());
    if (hosted) {
      await writeFile(`${out}.token`, await page.evaluate(() => Object.keys(localStorage)
        .filter((k) => k.startsWith("countershade-serve:")).map((k) => localStorage.getItem(k)).join("")));
    }
  }
} finally {
  await browser.close();
  server?.close();
}
if (blocked.length) throw new Error(`the Content-Security-Policy blocked ${blocked.length}: ${blocked[0]}`);
