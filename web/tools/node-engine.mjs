// The WebAssembly engine under Node.js, for the tests and tools: the build's
// countershade-engine.js and .wasm ($COUNTERSHADE_WEB_ENGINE, else build/web_engine). Node.js is
// handed the .wasm's bytes, because the glue's fetch() cannot read a file path.

import { readFileSync } from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath } from "node:url";

import { loadEngine } from "../engine.js";

export function nodeEngine() {
  const here = path.dirname(fileURLToPath(import.meta.url));
  const folder = process.env.COUNTERSHADE_WEB_ENGINE ?? path.join(here, "../../build/web_engine");
  const factory = createRequire(import.meta.url)(path.resolve(folder, "countershade-engine.js"));
  return loadEngine(factory, { wasmBinary: readFileSync(path.resolve(folder, "countershade-engine.wasm")) });
}
