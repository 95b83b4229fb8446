// Where a browser session keeps its answers: every row goes to localStorage before the next
// question appears, so a reload resumes at the first unanswered question; with a post URL each
// row is also sent to the server, in order, and sent again until the server acknowledges it.
// A reload can come after the server has taken a row but before the page has heard so; the row is
// then sent again. Each POST carries an Idempotency-Key header naming the session and the row's
// place in it, the same on every attempt, so the server keeps the first and acknowledges repeats.

// The browser's own columns, after the app's (docs/data-formats.md): the window, the chinrest's
// estimates with --chinrest (empty otherwise), and how the stimuli reached the screen (as the
// app's sidecar records it: 8-bit, or a 16-bit set through the dither).
export const BROWSER_COLUMNS = [
  "device_pixel_ratio", "window_width", "window_height", "refresh_hz", "user_agent",
  "css_px_per_mm", "viewing_distance_mm", "stimulus_bits", "output_path",
];
// The adjustment study's columns: the app's, then the browser's.
export const COLUMNS = [
  "subject", "scene", "sigma", "question", "lambda", "method", "lambda_step", "lambda_index", "lambda_max",
  "start_index", "repetition", "session", "trial", "side", "n_keypresses", "rt_ms", "revision", "timestamp_utc",
  "stimulus_set", "app_version", "sequence", ...BROWSER_COLUMNS,
];

// The browser's columns of a row, from what the page measured and the study's bits.
export function browserFields(environment, bits) {
  return {
    stimulus_bits: bits, output_path: bits === 16 ? "dither" : "8-bit",
    device_pixel_ratio: window.devicePixelRatio, window_width: window.innerWidth, window_height: window.innerHeight,
    refresh_hz: environment.refresh_hz ?? "", user_agent: navigator.userAgent,
    css_px_per_mm: environment.css_px_per_mm ?? "", viewing_distance_mm: environment.viewing_distance_mm ?? "",
  };
}

// One CSV field, quoted when it holds a comma, a quote or a line break (RFC 4180).
export function csvField(value) {
  const text = String(value);
  return /[",\r\n]/.test(text) ? `"${text.replaceAll('"', '""')}"` : text;
}
export const csvLine = (fields) => fields.map(csvField).join(",") + "\n";

export class SessionStore {
  // columns: the CSV's, in order (the adjustment study's by default).
  constructor(storage, key, postUrl = null, fetchImpl = globalThis.fetch?.bind(globalThis), columns = COLUMNS) {
    this.columns = columns;
    this.storage = storage;
    this.key = key;
    this.postUrl = postUrl;
    this.fetch = fetchImpl;
    const saved = JSON.parse(storage.getItem(key) ?? "null");
    this.rows = saved?.rows ?? [];   // every row: an object by column
    this.posted = saved?.posted ?? 0; // rows the server has acknowledged
    this.sending = false;
    this.backoff = 0;
    this.refusal = null; // the status of the server's last refusal of the row it is sending
    this.headers = {}; // sent with every POST (countershade serve's token)
  }

  save() {
    this.storage.setItem(this.key, JSON.stringify({ rows: this.rows, posted: this.posted }));
  }

  // Keeps the row (synchronously, before returning) and starts sending what is not acknowledged.
  add(row) {
    this.rows.push(row);
    this.save();
    this.flush();
  }

  // The latest answer to each (plan index, question): what a resume needs.
  answered() {
    const out = new Map();
    for (const row of this.rows) out.set(`${row.plan_index},${row.question_index}`, { lambdaIndex: Number(row.lambda_index), revision: Number(row.revision) });
    return out;
  }

  csv() {
    return csvLine(this.columns) + this.rows.map((row) => csvLine(this.columns.map((c) => row[c] ?? ""))).join("");
  }

  // The Idempotency-Key of row `index`: the session's storage key (URI-encoded: a header holds
  // ASCII only, and a subject ID need not) and the index.
  rowKey(index) {
    return `${encodeURIComponent(this.key)}:${index}`;
  }

  // Sends the rows in order, one at a time, each until the server answers 2xx; after a failure it
  // waits 100 ms, doubling up to 5 s while the server keeps failing. `refusal` keeps the status of
  // the last answer that refused the row itself (a 4xx other than a timeout or a rate limit),
  // which no number of retries is likely to change; null while rows go through or merely fail.
  async flush() {
    if (!this.postUrl || this.sending) return;
    this.sending = true;
    try {
      while (this.posted < this.rows.length) {
        const row = this.rows[this.posted];
        let ok = false;
        try {
          const response = await this.fetch(this.postUrl, {
            method: "POST",
            headers: { "Content-Type": "text/csv", "Idempotency-Key": this.rowKey(this.posted), ...this.headers },
            body: csvLine(this.columns) + csvLine(this.columns.map((c) => row[c] ?? "")),
          });
          ok = response.ok;
          const refused = response.status >= 400 && response.status < 500 && response.status !== 408 && response.status !== 429;
          this.refusal = refused ? response.status : null;
        } catch {
          ok = false;
          this.refusal = null;
        }
        if (ok) {
          ++this.posted;
          this.save();
          this.backoff = 0;
        } else {
          this.backoff = Math.min(5000, this.backoff ? 2 * this.backoff : (this.retryMs ?? 100));
          await new Promise((resolve) => setTimeout(resolve, this.backoff));
        }
      }
    } finally {
      this.sending = false;
    }
  }
}
