// The page of an exported study: asks for the participant's id (or takes ?subject=…&session=…),
// checks the browser (window size, refresh rate), optionally measures the screen with the virtual
// chinrest (recorded, never used to rescale), runs the adjustment or forced-choice session and
// offers the CSV.

import { loadEngine } from "./engine.js";
import { CountershadeAdjustPlugin } from "./plugin-adjust.js";
import { CountershadeChoicePlugin } from "./plugin-choice.js";

const study = window.COUNTERSHADE_STUDY;
const SUBJECT = /^[A-Za-z0-9_-]{1,64}$/;

function askSubject() {
  return new Promise((resolve) => {
    const form = document.createElement("form");
    const label = document.createElement("label");
    label.textContent = "Participant id (letters, digits, '-', '_'): ";
    const input = document.createElement("input");
    input.name = "subject";
    const go = document.createElement("button");
    go.textContent = "Start";
    form.append(label, input, go);
    document.body.appendChild(form);
    form.addEventListener("submit", (e) => {
      e.preventDefault();
      if (!SUBJECT.test(input.value)) return void (label.textContent = "Please use only letters, digits, '-' and '_': ");
      form.remove();
      resolve(input.value);
    });
    input.focus();
  });
}

// The end: the answers to download, and whether the study's server has them all. While rows are
// still unsent (the server or the network failing) the page says so, since a participant who
// closed it then would take them away, and says when they have arrived; where the server refuses
// a row outright, it asks for the file instead of patience.
function offerCsv(csv, subject, session, kind) {
  const link = document.createElement("a");
  link.href = URL.createObjectURL(new Blob([csv], { type: "text/csv" }));
  link.download = `${subject}_s${String(session).padStart(2, "0")}${kind}.csv`; // the app's file names
  link.textContent = "Download the answers (CSV)";
  link.id = "countershade-download";
  const p = document.createElement("p");
  p.id = "countershade-end";
  const status = document.createTextNode("");
  p.append(status, link);
  document.body.appendChild(p);
  const store = window.countershadeSession?.store;
  const update = () => {
    const left = store?.postUrl ? store.rows.length - store.posted : 0;
    const answers = `${left} ${left === 1 ? "answer" : "answers"}`;
    status.textContent = left === 0
      ? "Thank you. All answers are saved. "
      : store.refusal
        ? `Thank you. The study's server did not accept ${answers} (HTTP ${store.refusal}): please download them and send the file to the experimenter. `
        : `Thank you. ${answers} ${left === 1 ? "is" : "are"} still being sent: please keep this page open until it says that all answers are saved, or download them and send the file to the experimenter. `;
    if (left > 0) setTimeout(update, 250);
  };
  update();
}

// The virtual chinrest, measured once per session: kept in localStorage, so a reload resumes
// without measuring again. The page is never rescaled (resize_units "none").
function chinrest(key, environment) {
  const saved = JSON.parse(window.localStorage.getItem(key) ?? "null");
  if (saved) {
    Object.assign(environment, saved);
    return [];
  }
  return [{
    type: window.jsPsychVirtualChinrest, resize_units: "none",
    on_finish: (data) => {
      const measured = { css_px_per_mm: data.px2mm, viewing_distance_mm: data.view_dist_mm };
      window.localStorage.setItem(key, JSON.stringify(measured));
      Object.assign(environment, measured);
    },
  }];
}

// The study logic (WebAssembly); without it the page says so and records nothing.
async function engineOrMessage() {
  try {
    const started = performance.now();
    const engine = await loadEngine();
    window.countershadeEngineSeconds = (performance.now() - started) / 1000; // for bench/web
    return engine;
  } catch (error) {
    const p = document.createElement("p");
    p.id = "countershade-unsupported";
    p.textContent = `This browser cannot run the study (WebAssembly: ${error.message}). Please use a current Chrome, Edge, Firefox or Safari.`;
    document.body.appendChild(p);
    return null;
  }
}

// A 16-bit study needs WebGL2 for its dither; without it the page says so and records nothing.
function hasWebGl2() {
  if (document.createElement("canvas").getContext("webgl2")) return true;
  const p = document.createElement("p");
  p.id = "countershade-unsupported";
  p.textContent = "This study shows images with more than 8 bits, which needs WebGL2, and this browser has none: please use a current Chrome, Edge, Firefox or Safari with hardware acceleration on.";
  document.body.appendChild(p);
  return false;
}

// Where a study is hosted by `countershade serve`, the server's countershade-serve.json says
// where to claim a session and where to send rows; a static host has no such file.
async function servedBy() {
  try {
    const response = await fetch("countershade-serve.json", { cache: "no-store" });
    return response.ok ? await response.json() : null;
  } catch {
    return null;
  }
}

function say(id, text) {
  const p = document.createElement("p");
  p.id = id;
  p.textContent = text;
  document.body.appendChild(p);
}

// The browser's own token for a session: 128 random bits, kept in localStorage so that a reload
// claims the same session and sends its rows under the same token. The server keeps its hash.
function browserToken(key) {
  let token = window.localStorage.getItem(key);
  if (!/^[0-9a-f]{32}$/.test(token ?? "")) {
    token = [...crypto.getRandomValues(new Uint8Array(16))].map((b) => b.toString(16).padStart(2, "0")).join("");
    window.localStorage.setItem(key, token);
  }
  return token;
}

const CLAIM_REFUSED = {
  403: "This link is not valid. Please use the link you were given.",
  409: "This participant id already has a session in another browser. Please check the id.",
  410: "This link has already been used in another browser. Please go on in that browser, or ask for a new link.",
};

// Claims the session of the link (?link=…), or in an open study the session of the id the
// participant gives; retries while the server cannot be reached. {subject, session, token}, or
// null once the page has said why the study cannot start.
async function claimSession(served, params) {
  const link = params.get("link") ?? "";
  let body;
  if (/^[0-9a-f]{32}$/.test(link)) body = { link };
  else if (served.open) body = { subject: await subjectOf(params), session: sessionOf(params) };
  else return void say("countershade-error", "This study is open by link only: please use the link you were given.");
  const token = browserToken(`countershade-serve:${study.set.sha256}:${body.link ?? `${body.subject}:${body.session}`}`);
  for (let wait = 100; ; wait = Math.min(5000, 2 * wait)) {
    const response = await fetch(served.claim, {
      method: "POST", body: JSON.stringify(body),
      headers: { "Content-Type": "application/json", Authorization: `Bearer ${token}` },
    }).catch(() => null);
    if (response?.ok) return { ...(await response.json()), token };
    if (response && response.status < 500 && response.status !== 429)
      return void say("countershade-error", CLAIM_REFUSED[response.status] ?? `The study cannot start (${response.status}).`);
    await new Promise((resolve) => setTimeout(resolve, wait));
  }
}

const subjectOf = async (params) => (SUBJECT.test(params.get("subject") ?? "") ? params.get("subject") : await askSubject());
const sessionOf = (params) => Math.max(1, Math.min(99, Number.parseInt(params.get("session") ?? "1", 10) || 1));

async function start() {
  document.title = study.title;
  const engine = await engineOrMessage();
  if (!engine || (study.bits === 16 && !hasWebGl2())) return;
  CountershadeAdjustPlugin.engine = engine;
  CountershadeChoicePlugin.engine = engine;
  const choice = study.study === "forced_choice";
  const params = new URLSearchParams(window.location.search);
  const served = await servedBy();
  let subject, session;
  if (served) {
    const claimed = await claimSession(served, params);
    if (!claimed) return;
    ({ subject, session } = claimed);
    study.post_url = served.rows;
    study.post_headers = { Authorization: `Bearer ${claimed.token}` };
  } else {
    subject = await subjectOf(params);
    session = sessionOf(params);
  }
  const spec = params.get("observer") ?? "";
  const model = study.model && /^model:\d{1,15}$/.test(spec);
  const observer = model ? spec
                         : choice ? (/^weibull:[0-9.]+,[0-9.]+,\d{1,15}$/.test(spec) ? spec : null)
                                  : (/^simulated:\d{1,15}$/.test(spec) ? spec : null);
  const jsPsych = window.initJsPsych({});
  const environment = {};
  const timeline = [{
    type: window.jsPsychBrowserCheck,
    skip_features: ["webcam", "microphone"],
    on_finish: (data) => Object.assign(environment, { refresh_hz: data.vsync_rate, device_pixel_ratio: window.devicePixelRatio }),
  }];
  if (study.chinrest) timeline.push(...chinrest(`countershade-chinrest:${study.set.sha256}:${subject}:${session}`, environment));
  timeline.push({ type: choice ? CountershadeChoicePlugin : CountershadeAdjustPlugin, study, subject, session, environment, observer,
                  on_finish: (data) => offerCsv(data.csv, subject, session, choice ? ".forced-choice" : "") });
  await jsPsych.run(timeline);
}

start();
