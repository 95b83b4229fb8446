// The browser's answer store without a browser: rows kept synchronously, CSV as RFC 4180, a
// server that refuses the first two POSTs of every row still ends with every row once, in order,
// and a row sent again after a reload carries the key the server deduplicates by.

import { test } from "node:test";
import assert from "node:assert/strict";

import { SessionStore, csvField } from "../store.js";

class MemoryStorage {
  constructor() {
    this.items = new Map();
  }
  getItem(k) {
    return this.items.has(k) ? this.items.get(k) : null;
  }
  setItem(k, v) {
    this.items.set(k, String(v));
  }
}

test("text from a file is quoted, never split", () => {
  assert.equal(csvField('a,"b"'), '"a,""b"""');
  assert.equal(csvField("<script>x</script>"), "<script>x</script>");
});

test("every row reaches a refusing server exactly once, in order", async () => {
  const received = [];
  const attempts = new Map();
  const fetch = async (url, { body }) => {
    const row = body.split("\n")[1];
    attempts.set(row, (attempts.get(row) ?? 0) + 1);
    if (attempts.get(row) <= 2) return { ok: false };
    received.push(row);
    return { ok: true };
  };
  const storage = new MemoryStorage();
  const store = new SessionStore(storage, "k", "http://localhost/collect", fetch);
  store.retryMs = 1;
  for (let i = 0; i < 5; ++i) store.add({ subject: "P01", trial: i + 1, question: "low", lambda_index: i, revision: 0, plan_index: i, question_index: 0 });
  while (store.posted < 5) await new Promise((r) => setTimeout(r, 5));
  assert.equal(received.length, 5);
  assert.deepEqual(received.map((r) => r.split(",")[12]), ["1", "2", "3", "4", "5"]);
  const reloaded = new SessionStore(storage, "k", null);
  assert.equal(reloaded.rows.length, 5, "kept across a reload");
  assert.equal(reloaded.posted, 5);
  assert.deepEqual(reloaded.answered().get("3,0"), { lambdaIndex: 3, revision: 0 });
});

test("a row whose acknowledgement a reload cut off goes again under the same Idempotency-Key", async () => {
  const keys = [];
  const storage = new MemoryStorage();
  // The server takes the row, but the page is gone before it hears so: posted stays 0.
  const lost = new SessionStore(storage, "countershade:abc:Zoë 1:1", "http://localhost/collect", (url, { headers }) => {
    keys.push(headers["Idempotency-Key"]);
    return new Promise(() => {});
  });
  lost.add({ subject: "Zoë 1", trial: 1, question: "low", lambda_index: 2, revision: 0, plan_index: 0, question_index: 0 });
  const resumed = new SessionStore(storage, "countershade:abc:Zoë 1:1", "http://localhost/collect", async (url, { headers }) => {
    keys.push(headers["Idempotency-Key"]);
    return { ok: true };
  });
  resumed.add({ subject: "Zoë 1", trial: 2, question: "high", lambda_index: 4, revision: 0, plan_index: 0, question_index: 1 });
  while (resumed.posted < 2) await new Promise((r) => setTimeout(r, 5));
  assert.deepEqual(keys, ["countershade%3Aabc%3AZo%C3%AB%201%3A1:0", "countershade%3Aabc%3AZo%C3%AB%201%3A1:0",
                          "countershade%3Aabc%3AZo%C3%AB%201%3A1:1"]);
  assert.ok(keys.every((k) => /^[\x21-\x7e]+$/.test(k)), "a header value of visible ASCII");
});

test("a refusal of the row itself is kept; timeouts, rate limits and failures are not", async () => {
  const answers = [{ ok: false, status: 503 }, { ok: false, status: 429 }, { ok: false, status: 408 },
                   { ok: false, status: 422 }, { ok: false, status: 403 }, { ok: true, status: 201 }];
  const seen = [];
  let store;
  const fetch = async () => {
    seen.push(store.refusal); // what the store said before this attempt
    return answers[seen.length - 1];
  };
  store = new SessionStore(new MemoryStorage(), "k", "http://localhost/collect", fetch);
  store.retryMs = 1;
  store.add({ subject: "P01", trial: 1, question: "low", lambda_index: 0, revision: 0, plan_index: 0, question_index: 0 });
  while (store.posted < 1) await new Promise((r) => setTimeout(r, 5));
  assert.deepEqual(seen, [null, null, null, null, 422, 403]);
  assert.equal(store.refusal, null, "cleared once the row goes through");
});
