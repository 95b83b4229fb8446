// Prints, as JSON, the welcome text an exported study shows and whether any script from the
// study's texts ran (window.injected), for the test that text from a set never becomes markup.
//   node web/tools/browser-welcome.mjs STUDY_DIR

import puppeteer from "puppeteer-core";

import { serve } from "./static-server.mjs";

const [dir] = process.argv.slice(2);
const server = await serve(dir);
const browser = await puppeteer.launch({ executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium-headless-shell", args: ["--no-sandbox"] });
try {
  const page = await browser.newPage();
  await page.goto(`http://127.0.0.1:${server.address().port}/?subject=P01`);
  await page.waitForFunction(() => window.countershadeSession?.t0 !== undefined, { timeout: 60000 });
  await new Promise((r) => setTimeout(r, 200));
  console.log(JSON.stringify(await page.evaluate(() => ({
    text: window.countershadeSession.message.textContent,
    injected: window.injected ?? null,
    bold: document.querySelectorAll("b").length,
  }))));
} finally {
  await browser.close();
  server.close();
}
