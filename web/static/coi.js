// Where the browser lacks WebAssembly JavaScript Promise Integration (JSPI:
// Firefox, Safari), a lesson's requests wait for the game on memory the
// page shares with the lesson's worker, which needs the page to be
// cross-origin isolated (lesson_host.js). A server that sends the headers
// does that itself; otherwise this registers coi_sw.js, which adds them,
// and reloads the page once, when the service worker is ready, so that the
// page is loaded through it. Nothing happens where JSPI is there, the page
// is already isolated, or service workers are not available (a page not
// served from https or localhost); a page that is still not isolated after
// that one reload is left as it is (its lessons then say why they cannot
// run).
(function () {
  "use strict";
  const jspi =
    typeof WebAssembly === "object" &&
    (typeof WebAssembly.Suspending === "function" || typeof WebAssembly.Suspender === "function");
  const KEY = "lightcone-isolation-reload";
  if (self.crossOriginIsolated) {
    // Isolated: a later load that is not (a hard reload skips the service
    // worker) may reload once again.
    try {
      sessionStorage.removeItem(KEY);
    } catch (e) {
      // nothing to clear
    }
    return;
  }
  if (jspi || !self.isSecureContext || !("serviceWorker" in navigator)) return;
  let reloaded = false;
  try {
    reloaded = sessionStorage.getItem(KEY) === "1";
  } catch (e) {
    return; // no session storage: a reload could not be bounded
  }
  if (reloaded) return;
  navigator.serviceWorker
    .register("./coi_sw.js")
    .then(() => navigator.serviceWorker.ready)
    .then(() => {
      sessionStorage.setItem(KEY, "1");
      location.reload();
    })
    .catch((e) => console.warn("lightcone: cross-origin isolation not set up: " + e));
})();
