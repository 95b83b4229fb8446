// Debian's headless Chromium through puppeteer-core (never a downloaded browser), as every browser
// tool here starts it: $CHROMIUM names another binary; sRGB output, so screenshots hold the pixels
// the page drew.

import puppeteer from "puppeteer-core";

export function launchChromium(extraArgs = []) {
  return puppeteer.launch({
    executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium-headless-shell",
    args: ["--no-sandbox", "--force-color-profile=srgb", ...extraArgs],
  });
}
