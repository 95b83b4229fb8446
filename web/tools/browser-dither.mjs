// Opens an exported 16-bit study in Debian's headless Chromium (WebGL2 through SwiftShader),
// starts the session and reads back the first image of the trial over 64 consecutive frames as
// the page drew them, for the dither test.
//   node web/tools/browser-dither.mjs STUDY_DIR OUT.json

import { writeFile } from "node:fs/promises";

import { openStudy } from "./chromium.mjs";

const [dir, out] = process.argv.slice(2);
const { page, close } = await openStudy(dir, { args: ["--enable-unsafe-swiftshader", ...(process.env.CHROMIUM_ARGS ?? "").split(" ").filter(Boolean)] });
try {
  await page.waitForFunction(() => window.countershadeSession?.t0 !== undefined ||
                                             document.getElementById("countershade-unsupported"), { timeout: 60000 });
  const unsupported = await page.evaluate(() => document.getElementById("countershade-unsupported")?.textContent ?? null);
  if (unsupported !== null) {
    await writeFile(out, JSON.stringify({ unsupported, stored: await page.evaluate(() => window.localStorage.length) }));
  } else {
    await page.keyboard.press("Enter");
    await page.waitForFunction(() => window.countershadeSession.deep.items.length > 0, { timeout: 60000 });
    await page.evaluate(() => (window.countershadeDitherCapture = { frames: 64 }));
    await page.waitForFunction(() => window.countershadeDitherCapture.taken?.length === 64, { timeout: 120000, polling: 50 });
    await writeFile(out, JSON.stringify({ frames: await page.evaluate(() => window.countershadeDitherCapture.taken) }));
  }
} finally {
  await close();
}
