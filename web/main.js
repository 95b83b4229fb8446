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

function offerCsv(csv, subject, session, kind) {
  const link = document.createElement("a");
  link.href = URL.createObjectURL(new Blob([csv], { type: "text/csv" }));
  link.download = `${subject}_s${String(session).padStart(2, "0")}${kind}.csv`; // the app's file names
  link.textContent = "Download the answers (CSV)";
  link.id = "countershade-download";
  const p = document.createElement("p");
  p.textContent = "Thank you. All answers are saved. ";
  p.appendChild(link);
  document.body.appendChild(p);
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

async function start() {
  document.title = study.title;
  const engine = await engineOrMessage();
  if (!engine || (study.bits === 16 && !hasWebGl2())) return;
  CountershadeAdjustPlugin.engine = engine;
  CountershadeChoicePlugin.engine = engine;
  const choice = study.study === "forced_choice";
  const params = new URLSearchParams(window.location.search);
  const subject = SUBJECT.test(params.get("subject") ?? "") ? params.get("subject") : await askSubject();
  const session = Math.max(1, Math.min(99, Number.parseInt(params.get("session") ?? "1", 10) || 1));
  // ?observer=simulated:SEED (adjustment) or weibull:ALPHA,BETA,SEED (forced choice): the app's
  // simulated observer answers (pilots and tests); model:SEED answers from the prediction the page
  // was exported with (export-web --model-ppd).
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
