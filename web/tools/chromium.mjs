// Debian's headless Chromium through puppeteer-core (never a downloaded browser), as every browser
// tool here starts it: $CHROMIUM names another binary; sRGB output, so screenshots hold the pixels
// the page drew.

import puppeteer from "puppeteer-core";

import { serve } from "./static-server.mjs";

export function launchChromium(extraArgs = []) {
  return puppeteer.launch({
    executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium-headless-shell",
    args: ["--no-sandbox", "--force-color-profile=srgb", ...extraArgs],
  });
}

// An exported study served on loopback and opened for subject P01 in a page of the given size
// (CSS pixels) and device scale factor; close() ends both.
export async function openStudy(dir, { width = 900, height = 600, dpr = 1, args = [] } = {}) {
  const server = await serve(dir);
  const browser = await launchChromium(args);
  const close = async () => {
    await browser.close();
    server.close();
  };
  try {
    const page = await browser.newPage();
    await page.setViewport({ width, height, deviceScaleFactor: dpr });
    await page.goto(`http://127.0.0.1:${server.address().port}/?subject=P01`);
    return { page, close };
  } catch (error) {
    await close();
    throw error;
  }
}
