// A static file server for a study folder on a free loopback port, for the browser tests (any
// static server does for a real study).

import { createServer } from "node:http";
import { readFile } from "node:fs/promises";
import { extname, join, normalize } from "node:path";

const TYPES = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css", ".png": "image/png", ".wasm": "application/wasm" };

// A static file server for the study folder on a free loopback port. With `collect`, it also
// takes POSTs to /collect as docs/online-study.md asks of a server: it refuses the first `refuse`
// attempts at each row (with `status`, 503 by default), passes each row it accepts to collect(row),
// and acknowledges a
// repeated Idempotency-Key without collecting again. A repeat whose row differs from the first,
// or a POST without a key, is collected as an "ERROR" line, which fails the tests' comparison.
export function serve(root, collect = null, refuse = 0, status = 503) {
  const attempts = new Map();
  const taken = new Map(); // Idempotency-Key → the row taken under it
  const server = createServer(async (req, res) => {
    if (req.method === "POST" && collect) {
      let body = "";
      for await (const chunk of req) body += chunk;
      const row = body.split("\n")[1];
      const key = req.headers["idempotency-key"];
      attempts.set(row, (attempts.get(row) ?? 0) + 1);
      if (attempts.get(row) <= refuse) {
        res.writeHead(status);
        return void res.end();
      }
      if (!key || (taken.has(key) && taken.get(key) !== row)) collect(`ERROR ${key ?? "no key"}: ${row}`);
      else if (!taken.has(key)) {
        taken.set(key, row);
        collect(row);
      }
      res.writeHead(200);
      return void res.end();
    }
    const asked = normalize(decodeURIComponent(new URL(req.url, "http://x").pathname)).replace(/^(\.\.[/\\])+/, "");
    const path = asked === "/" ? "index.html" : asked;
    try {
      const body = await readFile(join(root, path));
      res.writeHead(200, { "Content-Type": TYPES[extname(path)] ?? "application/octet-stream" });
      res.end(body);
    } catch {
      res.writeHead(404);
      res.end();
    }
  });
  return new Promise((resolve) => server.listen(0, "127.0.0.1", () => resolve(server)));
}

