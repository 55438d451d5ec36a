// A service worker that makes this origin's pages cross-origin isolated
// where the server does not say so itself (python3 -m http.server, most
// static hosts): it passes every same-origin request through and adds the
// two headers that isolation needs (Cross-Origin-Opener-Policy:
// same-origin, Cross-Origin-Embedder-Policy: require-corp). An isolated
// page may share memory with its workers (SharedArrayBuffer), which is how
// a lesson's requests wait for the game in a browser without JSPI (Firefox,
// Safari; lesson_host.js). coi.js registers it, only in such a browser.
// Everything Lightcone loads comes from its own origin, so requiring
// CORP of cross-origin resources costs nothing here.
self.addEventListener("install", () => self.skipWaiting());
self.addEventListener("activate", (e) => e.waitUntil(self.clients.claim()));
self.addEventListener("fetch", (e) => {
  const request = e.request;
  if (new URL(request.url).origin !== self.location.origin) return;
  // A request the browser only wants from its cache is not ours to fetch.
  if (request.cache === "only-if-cached" && request.mode !== "same-origin") return;
  e.respondWith(
    fetch(request).then((response) => {
      if (response.status === 0) return response; // opaque: no headers to set
      const headers = new Headers(response.headers);
      headers.set("Cross-Origin-Opener-Policy", "same-origin");
      headers.set("Cross-Origin-Embedder-Policy", "require-corp");
      return new Response(response.body, { status: response.status, statusText: response.statusText, headers });
    }),
  );
});
