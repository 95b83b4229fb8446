// Opens an exported forced-choice study (spatial) in Debian's headless Chromium at a device scale
// factor, starts the session and writes a screenshot of the first trial with what the page says
// it shows (the files and their device-pixel places), for the pixel test.
//   [WIDTH=… HEIGHT=…] node web/tools/browser-choice-shot.mjs STUDY_DIR DPR OUT.png

import { writeFile } from "node:fs/promises";

import { openStudy } from "./chromium.mjs";

const [dir, dpr, out] = process.argv.slice(2);

const { page, close } = await openStudy(dir, { width: Number(process.env.WIDTH ?? 900), height: Number(process.env.HEIGHT ?? 600), dpr: Number(dpr) });
try {
  await page.waitForFunction(() => window.countershadeSession?.t0 !== undefined, { timeout: 60000 });
  await page.keyboard.press("Enter");
  await page.waitForFunction(() => window.countershadeShown?.files?.length > 0, { timeout: 60000 });
  await new Promise((r) => setTimeout(r, 200));
  const shown = await page.evaluate(() => window.countershadeShown);
  await page.screenshot({ path: out });
  await writeFile(`${out}.json`, JSON.stringify({ ...shown, device_pixel_ratio: Number(dpr) }, null, 1));
} finally {
  await close();
}
