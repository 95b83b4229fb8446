// How long an exported study takes to start its WebAssembly engine (fetch, compile, instantiate)
// and to decode one condition's images from a local server, in headless Chromium (the first
// condition, loaded while the welcome text is shown).
//   build/bin/countershade export-web SET/manifest.json -o /tmp/study && node bench/web/preload.mjs /tmp/study

import puppeteer from "puppeteer-core";

import { serve } from "../../web/tools/static-server.mjs";

const [dir] = process.argv.slice(2);
const server = await serve(dir);
const browser = await puppeteer.launch({ executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium-headless-shell", args: ["--no-sandbox"] });
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 2400, height: 1400, deviceScaleFactor: 1 });
  await page.goto(`http://127.0.0.1:${server.address().port}/?subject=bench`);
  await page.waitForFunction(() => window.countershadeSession?.loaded?.size > 0, { timeout: 120000, polling: 10 });
  const [condition, seconds] = await page.evaluate(() => Object.entries(window.countershadeSession.loadSeconds)[0]);
  const images = await page.evaluate((c) => 1 + window.COUNTERSHADE_STUDY.conditions[c].images.length, Number(condition));
  const engine = await page.evaluate(() => window.countershadeEngineSeconds);
  console.log(`engine: countershade-engine.wasm ready in ${engine.toFixed(3)} s`);
  console.log(`preload: condition ${condition}, ${images} images decoded in ${seconds.toFixed(3)} s`);
} finally {
  await browser.close();
  server.close();
}
