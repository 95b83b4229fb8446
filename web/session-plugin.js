// A whole countershade session as one jsPsych 8 trial: the plugin class both studies use. The
// session object (plugin-adjust.js, plugin-choice.js) runs the trials; the plugin hands it the
// page, the engine and the trial's parameters, and finishes the jsPsych trial with its result.

const type = (name) => window.jsPsychModule?.ParameterType[name];

// makeSession(displayElement, engine, trial) returns an object whose start() resolves to
// {end, answers, csv, …} once the session ends.
export function sessionPlugin(name, makeSession) {
  return class {
    static info = {
      name,
      version: "1.0.0",
      parameters: {
        study: { type: type("OBJECT"), default: undefined },
        subject: { type: type("STRING"), default: undefined },
        session: { type: type("INT"), default: 1 },
        environment: { type: type("OBJECT"), default: {} },
        observer: { type: type("STRING"), default: null },
      },
      data: { end: { type: type("STRING") }, answers: { type: type("INT") }, csv: { type: type("STRING") } },
    };

    // The WebAssembly engine (engine.js's loadEngine), set once before the timeline runs: it is
    // no trial parameter, because jsPsych copies those and the engine is no plain object.
    static engine = null;

    constructor(jsPsych) {
      this.jsPsych = jsPsych;
    }

    async trial(displayElement, trial) {
      let session;
      try {
        session = makeSession(displayElement, this.constructor.engine, trial);
      } catch (error) {
        // e.g. answers stored by another version of the study: say so, and record nothing more
        const p = document.createElement("p");
        p.id = "countershade-error";
        p.textContent = `The study cannot go on: ${error.message}`;
        displayElement.replaceChildren(p);
        return;
      }
      window.countershadeSession = session;
      const result = await session.start();
      displayElement.innerHTML = "";
      this.jsPsych.finishTrial(result);
    }
  };
}
