// The page's side of a lesson run in the browser: starts the lesson's
// worker (lesson_worker.js: Pyodide in a module Web Worker) and carries the
// lesson protocol's JSON lines (game/src/lesson/remote.rs) both ways. The
// game (Rust, compiled to wasm) calls it and polls it every frame:
//
//   lightconeLesson.open(name, source, limitSeconds)  a new worker for the
//       lesson `name` (its file name, the lesson's __file__) whose Python
//       is `source`; any running one is ended first
//   lightconeLesson.send(line)  a Down line to the worker: a call
//       {"call": hook, "args": [...], "snapshot": {...}} or the answer to a
//       request {"ok": v, "snapshot": {...}} / {"error": [kind, message],
//       "snapshot": {...}}; false when no worker runs
//   lightconeLesson.take()  the messages since the last take, oldest first:
//       {kind: "ready"} (Python and the package loaded; the lesson's code
//       has not run), {kind: "line", line} (an Up line: a request, or a
//       hook's {"done": ...}), {kind: "failed", error} (lessons cannot run:
//       Pyodide did not load, neither JSPI nor cross-origin isolation ...),
//       {kind: "ended", why} (the worker
//       broke down or crashed)
//   lightconeLesson.stop()  ends the worker (the game's time limit, a reload),
//       dropping what it sent that was not taken
//   lightconeLesson.state()  "none" (no worker: never opened, or stopped),
//       "loading", "ready", or "ended" (after "failed" or "ended")
//   lightconeLesson.onMessage(f)  has f() called after each message is
//       received (the game wakes on it and answers a request at once,
//       without waiting for its next frame)
//
// Nothing the worker sends is trusted (the lesson's Python can post
// messages of its own): a line over 16 Mi characters, or more than 10 000
// messages (of any kind) waiting to be taken, ends the worker with the
// reason; a message of no known kind is dropped without waking the game;
// a reason the worker gives is cut to 64 Ki characters.
// Nothing here times hooks: the worker raises TimeoutError in a hook past
// its limit, and the game calls stop() on one that still runs after.
//
// In a browser without JSPI (Firefox, Safari) a request cannot wait for
// the game's answer by stack switching; where the page is cross-origin
// isolated each worker is given a SharedArrayBuffer (the "channel") and
// waits on it instead: it marks such a request `blocking`, and the next
// send() writes the answer there (UTF-8, in chunks of CHANNEL_BYTES, the
// next one when the worker says {kind: "more"}) instead of posting it.
// coi_sw.js makes a page served without the headers cross-origin isolated.
(function () {
  "use strict";

  let worker = null;
  let current = "none";
  let received = [];
  let wake = null;
  // The protocol's bounds (lightcone_lesson::protocol::MAX_LINE).
  const MAX_LINE = 16 << 20;
  const MAX_WAITING = 10000;
  const MAX_REASON = 64 << 10;
  let junk = 0;
  const reason = (x) => String(x).slice(0, MAX_REASON);
  // The channel of a worker without JSPI (module doc): its layout is
  // lesson_worker.js's (two Int32, what the data holds and its length,
  // then the data).
  const CHANNEL_HEADER = 8;
  const CHANNEL_BYTES = 1 << 20;
  const MORE = 1;
  const LAST = 2;
  let channel = null;
  // Whether the worker waits on the channel for the answer to a request,
  // and the part of an answer not yet written there.
  let blocked = false;
  let pending = null;

  // Writes the next chunk of the pending answer and wakes the worker.
  function writeChunk() {
    const state = new Int32Array(channel, 0, 2);
    const data = new Uint8Array(channel, CHANNEL_HEADER);
    const n = Math.min(data.length, pending.bytes.length - pending.offset);
    data.set(pending.bytes.subarray(pending.offset, pending.offset + n));
    pending.offset += n;
    Atomics.store(state, 1, n);
    const last = pending.offset >= pending.bytes.length;
    Atomics.store(state, 0, last ? LAST : MORE);
    Atomics.notify(state, 0);
    if (last) pending = null;
  }

  // Ends the worker and forgets it (its late messages are ignored).
  function end(next) {
    if (worker) worker.terminate();
    worker = null;
    current = next;
  }

  function open(name, source, limitSeconds) {
    end("none");
    received = [];
    junk = 0;
    current = "loading";
    channel =
      typeof SharedArrayBuffer === "function" && self.crossOriginIsolated
        ? new SharedArrayBuffer(CHANNEL_HEADER + CHANNEL_BYTES)
        : null;
    blocked = false;
    pending = null;
    let w;
    try {
      w = new Worker("./lesson_worker.js", { type: "module" });
    } catch (e) {
      received.push({ kind: "failed", error: `the lesson's worker could not start: ${e}` });
      current = "ended";
      return;
    }
    worker = w;
    w.onmessage = (e) => {
      if (w !== worker) return;
      const m = e.data || {};
      if (received.length + junk >= MAX_WAITING) {
        received = [{ kind: "ended", why: `it sent more than ${MAX_WAITING} messages the game had not taken yet` }];
        end("ended");
        if (wake) wake();
        return;
      }
      if (m.kind === "line" && typeof m.line === "string" && m.line.length > MAX_LINE) {
        received.push({ kind: "ended", why: `it sent a line of ${m.line.length} characters (at most ${MAX_LINE})` });
        end("ended");
        if (wake) wake();
        return;
      }
      if (m.kind === "ready") {
        current = "ready";
        received.push({ kind: "ready" });
      } else if (m.kind === "line" && typeof m.line === "string") {
        blocked = m.blocking === true && channel !== null;
        received.push({ kind: "line", line: m.line });
      } else if (m.kind === "more" && pending) {
        writeChunk();
        return; // the worker's own business: the game is not woken
      } else if (m.kind === "failed") {
        received.push({ kind: "failed", error: reason(m.error) });
        end("ended");
      } else if (m.kind === "ended") {
        received.push({ kind: "ended", why: reason(m.why) });
        end("ended");
      } else {
        junk++; // counted against the bound until the next take
        return;
      }
      if (wake) wake();
    };
    // An uncaught error in the worker, or a worker script that did not load.
    w.onerror = (e) => {
      if (w !== worker) return;
      if (e && e.preventDefault) e.preventDefault();
      const why = e && e.message ? e.message : "its script could not be loaded (./lesson_worker.js)";
      received.push({ kind: "ended", why: `the lesson's worker stopped: ${why}` });
      end("ended");
    };
    w.onmessageerror = () => {
      if (w !== worker) return;
      received.push({ kind: "ended", why: "the lesson's worker sent a message that cannot be read" });
      end("ended");
    };
    w.postMessage({ kind: "open", name: String(name), source: String(source), limit: Number(limitSeconds), channel });
  }

  function send(line) {
    if (!worker) return false;
    if (blocked) {
      // The answer to the request the worker waits on: on the channel.
      blocked = false;
      pending = { bytes: new TextEncoder().encode(String(line)), offset: 0 };
      writeChunk();
      return true;
    }
    worker.postMessage({ kind: "line", line: String(line) });
    return true;
  }

  function take() {
    const taken = received;
    received = [];
    junk = 0;
    return taken;
  }

  // What the stopped worker sent and was not taken is dropped with it.
  function stop() {
    end("none");
    received = [];
  }

  function state() {
    return current;
  }

  function onMessage(f) {
    wake = typeof f === "function" ? f : null;
  }

  window.lightconeLesson = { open, send, take, stop, state, onMessage };
})();
