// A lesson's worker: Pyodide in a module Web Worker, started by
// lesson_host.js for one lesson (a reload starts a new worker). It speaks
// the protocol of a lesson run in its own process on the desktop
// (game/src/lesson/remote.rs), its JSON lines carried by postMessage:
//
//   page → worker  {kind: "open", name, source, limit}   once, first
//                  {kind: "line", line}   a call, or the answer to a request
//   worker → page  {kind: "ready"}        Python and the package loaded
//                  {kind: "line", line}   a request, or a hook's Done line
//                  {kind: "failed", error}  it cannot run lessons here
//                  {kind: "ended", why}   it broke down after "ready"
//
// The Python side (lightcone_web_child.py) runs each call; a request from
// the lesson's `World` must be synchronous for Python, so each hook is
// entered with stack switching (`callPromising`) and a request blocks on
// the game's answer with `pyodide.ffi.run_sync` (WebAssembly JavaScript
// Promise Integration, JSPI). Scenes and simulations are the engine's,
// compiled for the worker (lightcone_engine_web.js, wasm-bindgen), which
// the `lightcone._lightcone` stand-in calls. Everything is fetched from
// this origin: ./pyodide/ (the runtime and its standard library),
// ./python/ (the package and the protocol's Python) and the engine.

// The Python files, fetched from ./python/ and written under ROOT at the
// same paths (web.sh copies them there from py/, game/src/lesson/, web/python/).
const ROOT = "/opt/lightcone";
const PYTHON_FILES = [
  "lightcone/__init__.py",
  "lightcone/records.py",
  "lightcone/_lightcone.py",
  "lightcone_remote.py",
  "lightcone_bootstrap.py",
  "lightcone_web_child.py",
];

const post = (message) => self.postMessage(message);

// Lines from the page not yet taken by Python, and who waits for the next.
const inbox = [];
let waiting = null;

// The next line from the page (a call between hooks, an answer inside one).
function nextLine() {
  if (inbox.length > 0) return Promise.resolve(inbox.shift());
  return new Promise((resolve) => {
    waiting = resolve;
  });
}

let opened = false;

self.onmessage = (e) => {
  const m = e.data || {};
  if (m.kind === "open" && !opened) {
    opened = true;
    run(String(m.name), String(m.source), Number(m.limit)).catch((err) => {
      post({ kind: "ended", why: `the lesson's worker broke down: ${describe(err)}` });
    });
  } else if (m.kind === "line" && typeof m.line === "string") {
    if (waiting) {
      const w = waiting;
      waiting = null;
      w(m.line);
    } else {
      inbox.push(m.line);
    }
  }
};

// An error's message (a Python error's is its traceback).
function describe(err) {
  return err && err.message ? err.message : String(err);
}

// Whether this browser has JSPI (the standard API, or the one Chrome had
// behind a flag before it), which blocking requests need.
function hasJspi() {
  return typeof WebAssembly.Suspending === "function" || typeof WebAssembly.Suspender === "function";
}

// Loads everything, then runs the lesson's calls as they come.
async function run(name, source, limit) {
  if (!hasJspi()) {
    post({
      kind: "failed",
      error:
        "this browser cannot run lessons: it lacks WebAssembly JavaScript Promise Integration (JSPI); use Chrome or Edge 137 or newer",
    });
    return;
  }
  let pyodide, engine, files;
  try {
    [pyodide, engine, files] = await Promise.all([startPython(), startEngine(), fetchPython()]);
  } catch (err) {
    post({ kind: "failed", error: `the lesson's Python could not start: ${describe(err)}` });
    return;
  }
  let runCall;
  try {
    for (const [path, text] of files) {
      const full = `${ROOT}/${path}`;
      pyodide.FS.mkdirTree(full.slice(0, full.lastIndexOf("/")));
      pyodide.FS.writeFile(full, text);
    }
    pyodide.registerJsModule("lightcone_engine_web", { lightcone_call: engine.lightcone_call });
    // Python's side of a request: the line goes up, and the hook blocks
    // (run_sync) until the page's next line, the answer.
    pyodide.globals.set("_lightcone_up", (line) => post({ kind: "line", line }));
    pyodide.globals.set("_lightcone_next", nextLine);
    const start = pyodide.runPython(`
import sys
sys.path.insert(0, ${JSON.stringify(ROOT)})
import lightcone, lightcone_web_child
from pyodide.ffi import run_sync

def _lightcone_request(line, up=_lightcone_up, next_line=_lightcone_next):
    up(line)
    return run_sync(next_line())

del _lightcone_up, _lightcone_next
lightcone_web_child.start
`);
    // A hook over `limit` s gets a TimeoutError at its line (sys.monitoring,
    // lightcone_web_child.py); the game ends this worker if one still runs
    // a moment later (a long call into C).
    const child = start(name, source, pyodide.globals.get("_lightcone_request"), limit);
    start.destroy();
    runCall = child.run_call;
  } catch (err) {
    post({ kind: "failed", error: `the lesson's Python could not start: ${describe(err)}` });
    return;
  }
  post({ kind: "ready" });
  for (;;) {
    const line = await nextLine();
    // With stack switching: the hook may block on requests.
    const done = await runCall.callPromising(line);
    post({ kind: "line", line: done });
  }
}

// Pyodide, from ./pyodide/ (imported here, not at the top, so that a
// missing runtime is reported as "failed", not as a worker that never
// starts).
async function startPython() {
  const { loadPyodide } = await import("./pyodide/pyodide.mjs");
  const indexURL = new URL("./pyodide/", import.meta.url).href;
  return loadPyodide({ indexURL, env: { HOME: "/home/pyodide" } });
}

// The engine compiled for the worker (wasm-bindgen's --target web glue).
async function startEngine() {
  const engine = await import("./lightcone_engine_web.js");
  await engine.default();
  return engine;
}

// The Python files, as [path, text] pairs.
async function fetchPython() {
  return Promise.all(
    PYTHON_FILES.map(async (path) => {
      const url = new URL(`./python/${path}`, import.meta.url);
      const response = await fetch(url);
      if (!response.ok) throw new Error(`${url.pathname}: ${response.status} ${response.statusText}`);
      return [path, await response.text()];
    }),
  );
}
