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
// With neither JSPI nor the channel "open" is answered with "failed". Two
// more messages serve the channel: the page's answer to a `blocking`
// request goes there instead of in a "line", and the worker asks for each
// next chunk of it with {kind: "more"}.
//
// The Python side (lightcone_web_child.py) runs each call; a request from
// the lesson's `World` must be synchronous for Python. Where the browser
// has WebAssembly JavaScript Promise Integration (JSPI: Chrome, Edge),
// each hook is entered with stack switching (`callPromising`) and a
// request blocks on the game's answer with `pyodide.ffi.run_sync`.
// Elsewhere (Firefox, Safari) the page, when cross-origin isolated, gives
// the worker a SharedArrayBuffer (`channel` in "open"): a request is then
// posted with `blocking: true` and the worker waits on the buffer
// (`Atomics.wait`) until the page has written the answer there, in chunks
// of at most CHANNEL_BYTES (the worker asks for each next one with
// {kind: "more"}). Without either it cannot run lessons and says so.
// Scenes and simulations are the engine's,
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
// The page's SharedArrayBuffer, where it gave one (module doc).
let channel = null;

// The channel's layout (lesson_host.js writes it): two Int32 (what the
// data holds: 0 nothing, 1 a chunk with more to come, 2 the last chunk;
// and its length in bytes), then the data.
const CHANNEL_HEADER = 8;
const MORE = 1;
const LAST = 2;

self.onmessage = (e) => {
  const m = e.data || {};
  if (m.kind === "open" && !opened) {
    opened = true;
    if (typeof SharedArrayBuffer === "function" && m.channel instanceof SharedArrayBuffer) channel = m.channel;
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

// A message that cannot be read (an "open" whose shared buffer a page
// that is not isolated could not send): said, rather than a lesson that
// never starts.
self.onmessageerror = () => {
  post({ kind: "failed", error: "the lesson's worker got a message it cannot read (is the page cross-origin isolated?)" });
};

// An error's message (a Python error's is its traceback).
function describe(err) {
  return err && err.message ? err.message : String(err);
}

// Whether this browser has JSPI (the standard API, or the one Chrome had
// behind a flag before it), with which requests block by stack switching.
function hasJspi() {
  return typeof WebAssembly.Suspending === "function" || typeof WebAssembly.Suspender === "function";
}

// A request from Python without JSPI: the line goes up, and the worker
// waits on the channel for the answer, chunk by chunk (module doc).
function blockingRequest(line) {
  post({ kind: "line", line: String(line), blocking: true });
  const state = new Int32Array(channel, 0, 2);
  const data = new Uint8Array(channel, CHANNEL_HEADER);
  const decoder = new TextDecoder();
  let text = "";
  for (;;) {
    Atomics.wait(state, 0, 0);
    const kind = Atomics.load(state, 0);
    const length = Math.min(Atomics.load(state, 1), data.length);
    // Copied out of the shared memory (TextDecoder reads no shared views).
    text += decoder.decode(data.slice(0, length), { stream: kind === MORE });
    Atomics.store(state, 0, 0);
    if (kind !== MORE) return text;
    post({ kind: "more" });
  }
}

// Loads everything, then runs the lesson's calls as they come.
async function run(name, source, limit) {
  const jspi = hasJspi();
  if (!jspi && !channel) {
    post({
      kind: "failed",
      error:
        "this browser cannot run lessons here: it lacks WebAssembly JavaScript Promise Integration (JSPI), " +
        "and the page is not cross-origin isolated (the other way a lesson's requests can wait for the game); " +
        "use Chrome or Edge 137 or newer, or serve the page with the headers docs/web.md gives " +
        "(Cross-Origin-Opener-Policy: same-origin, Cross-Origin-Embedder-Policy: require-corp)",
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
    // until the answer: with JSPI (run_sync) until the page's next line,
    // else on the channel.
    pyodide.globals.set("_lightcone_up", (line) => post({ kind: "line", line }));
    pyodide.globals.set("_lightcone_next", nextLine);
    pyodide.globals.set("_lightcone_blocking", blockingRequest);
    const start = pyodide.runPython(`
import sys
sys.path.insert(0, ${JSON.stringify(ROOT)})
import lightcone, lightcone_web_child

if ${jspi ? "True" : "False"}:
    from pyodide.ffi import run_sync

    def _lightcone_request(line, up=_lightcone_up, next_line=_lightcone_next):
        up(line)
        return run_sync(next_line())
else:
    def _lightcone_request(line, blocking=_lightcone_blocking):
        return str(blocking(line))

del _lightcone_up, _lightcone_next, _lightcone_blocking
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
    // With stack switching where there is JSPI: the hook may block on
    // requests (without, it blocks on the channel).
    const done = jspi ? await runCall.callPromising(line) : runCall(line);
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
