// Opens an exported study in Debian's headless Chromium (through puppeteer-core, never a
// downloaded browser) at a device scale factor, starts the session, steps λ up twice and writes
// a screenshot of the trial with what the page says it shows (for the pixel test).
//   node web/tools/browser-shot.mjs STUDY_DIR DPR OUT.png

import { writeFile } from "node:fs/promises";

import { openStudy } from "./chromium.mjs";

const [dir, dpr, out] = process.argv.slice(2);

const { page, close } = await openStudy(dir, { width: Number(process.env.WIDTH ?? 900), height: Number(process.env.HEIGHT ?? 600), dpr: Number(dpr) });
try {
  await page.waitForFunction(() => window.countershadeSession?.t0 !== undefined, { timeout: 60000 });
  await page.keyboard.press("Enter");
  await page.waitForFunction(() => window.countershadeSession.ready(), { timeout: 60000 });
  for (const key of ["ArrowUp", "ArrowUp"]) await page.keyboard.press(key);
  await page.waitForFunction(() => window.countershadeShown?.lambda_index !== undefined);
  await new Promise((r) => setTimeout(r, 200));
  const shown = await page.evaluate(() => window.countershadeShown);
  await page.screenshot({ path: out });
  await writeFile(`${out}.json`, JSON.stringify({ ...shown, device_pixel_ratio: Number(dpr) }, null, 1));
} finally {
  await close();
}
