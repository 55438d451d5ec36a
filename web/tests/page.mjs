// The browser build's test: Debian's Chromium, headless, software WebGL2
// (SwiftShader), driven by playwright-core. For the default scene and for
// `?scene=ten_pucks`: the page draws its first frame, no console error or
// uncaught exception, and the screenshot is not blank (many colours, no
// colour on nearly all of it). Saves the default scene's screenshot.
//
//   node web/tests/page.mjs URL SCREENSHOT.png
//
// Prints one JSON line per page (first frame in ms since navigation) and
// exits 1 on any failure.
import { chromium } from "playwright-core";

const [base, shot] = process.argv.slice(2);
if (!base || !shot) {
  console.error("usage: node page.mjs URL SCREENSHOT.png");
  process.exit(2);
}

// Debian's Chromium on software WebGL2 (SwiftShader), with `extra` flags.
const launch = (extra) =>
  chromium.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist", "--no-sandbox", ...extra],
  });

// A school's server by name: a page not served over https or from
// localhost, which has no clipboard (the share test below).
const browser = await launch(["--host-resolver-rules=MAP school.test 127.0.0.1"]);

let failed = false;
// The default scene's screenshot, for the parity test against the window.
let defaultPng = null;
function fail(what) {
  console.error(`FAIL ${what}`);
  failed = true;
}

// A page of 1280×720 (in `context`, else a new one) and the console errors
// and uncaught exceptions it will have.
async function openPage(context = null) {
  const page = context ? await context.newPage() : await browser.newPage({ viewport: { width: 1280, height: 720 } });
  const errors = [];
  page.on("console", (m) => {
    if (m.type() === "error") errors.push(m.text());
  });
  page.on("pageerror", (e) => errors.push(`uncaught: ${e.message}`));
  return { page, errors };
}

// Gives `page` `window.lightconeTestPixels(base64Png)`: the PNG decoded by
// the page itself (no PNG decoder needed here), as `{ w, h, px }` with `px`
// its RGBA bytes.
async function addDecoder(page) {
  await page.addScriptTag({
    content: `window.lightconeTestPixels = async (data) => {
      const img = new Image();
      img.src = "data:image/png;base64," + data;
      await img.decode();
      const c = document.createElement("canvas");
      c.width = img.width;
      c.height = img.height;
      const ctx = c.getContext("2d");
      ctx.drawImage(img, 0, 0);
      return { w: img.width, h: img.height, px: ctx.getImageData(0, 0, img.width, img.height).data };
    };`,
  });
}

// Waits for the game's first frame on `page`.
const firstFrame = (page) =>
  page.waitForFunction(() => window.lightconeFirstFrameMs !== undefined, null, { timeout: 120_000 });

async function check(query, screenshot) {
  const { page, errors } = await openPage();
  const url = base + query;
  await page.goto(url);
  try {
    await firstFrame(page);
  } catch {
    fail(`${url}: no first frame in 120 s; console errors: ${JSON.stringify(errors)}`);
    await page.close();
    return;
  }
  const firstFrameMs = await page.evaluate(() => window.lightconeFirstFrameMs);
  // A few more frames: the panels' fonts, the views framed for the room
  // the panels leave.
  await page.waitForTimeout(2000);

  const png = await page.screenshot({ path: screenshot });
  if (query === "") defaultPng = png;
  // The screenshot's pixels, read back by the page itself (no PNG decoder
  // needed here): distinct colours (4 bits a channel) and the share of
  // the commonest one.
  await addDecoder(page);
  const stats = await page.evaluate(async (data) => {
    const { px } = await window.lightconeTestPixels(data);
    const counts = new Map();
    for (let i = 0; i < px.length; i += 4) {
      const k = ((px[i] >> 4) << 8) | ((px[i + 1] >> 4) << 4) | (px[i + 2] >> 4);
      counts.set(k, (counts.get(k) || 0) + 1);
    }
    const top = Math.max(...counts.values());
    return { colours: counts.size, commonest: top / (px.length / 4) };
  }, png.toString("base64"));
  // Frame times: the game draws once per animation frame (winit's redraw
  // on the web), so the gaps between animation frames over 3 s are its
  // frame times (ms; the game running, not paused on its title).
  await page.focus("canvas");
  await page.keyboard.press("Space");
  const frames = await page.evaluate(
    () =>
      new Promise((done) => {
        const gaps = [];
        let last = performance.now();
        const end = last + 3000;
        const tick = (now) => {
          gaps.push(now - last);
          last = now;
          if (now < end) requestAnimationFrame(tick);
          else {
            gaps.sort((a, b) => a - b);
            const q = (f) => Math.round(gaps[Math.floor(f * (gaps.length - 1))] * 10) / 10;
            done({ n: gaps.length, p50: q(0.5), p95: q(0.95), max: q(1) });
          }
        };
        requestAnimationFrame(tick);
      }),
  );
  await page.keyboard.press("Space");
  const cpu = await page.evaluate(() => window.lightconeFrameCpuMs);
  console.log(JSON.stringify({ url, firstFrameMs, frameMs: frames, frameCpuMs: cpu, ...stats, errors }));
  if (errors.length) fail(`${url}: console errors: ${JSON.stringify(errors)}`);
  if (stats.colours < 16 || stats.commonest > 0.95)
    fail(`${url}: the page looks blank (${stats.colours} colours, commonest ${stats.commonest})`);
  await page.close();
}

// Links, dropped files and the share key (K). The links are made here by
// the browser's own CompressionStream("deflate-raw") and base64url, and
// the share link is read back by its DecompressionStream: the format of
// game/src/links.rs, checked against another implementation both ways.
async function links() {
  const { page, errors } = await openPage();
  const started = () => firstFrame(page);
  const titled = (title) =>
    page.waitForFunction((t) => document.title === t, title, { timeout: 30_000 }).then(
      () => true,
      () => false,
    );
  await page.goto(base);
  await started();
  // On every page of this tab: the link's DATA both ways, by the browser's
  // own streams.
  const helpers = () => {
    window.packLink = async (text) => {
      const s = new Blob([text]).stream().pipeThrough(new CompressionStream("deflate-raw"));
      const bytes = new Uint8Array(await new Response(s).arrayBuffer());
      let bin = "";
      for (const b of bytes) bin += String.fromCharCode(b);
      return btoa(bin).replace(/[+]/g, "-").replace(/[/]/g, "_").replace(/=+$/, "");
    };
    window.unpackLink = async (data) => {
      const b64 = data.replace(/-/g, "+").replace(/_/g, "/");
      const bin = atob(b64 + "===".slice((b64.length + 3) % 4));
      const bytes = Uint8Array.from(bin, (c) => c.charCodeAt(0));
      const s = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate-raw"));
      return await new Response(s).text();
    };
  };
  await page.addInitScript(helpers);
  await page.evaluate(helpers);
  const shipped = await page.evaluate(async () => (await fetch("scenes/ten_pucks.toml")).text());
  const retitled = (title) => shipped.replace(/^title = .*$/m, `title = "${title}"`);

  // 1. A scene carried in the link's fragment opens (the tab's title is
  // the scene's).
  const data = await page.evaluate((t) => window.packLink(t), retitled("Linked by a test"));
  await page.goto(base + "#scene=" + data);
  await started();
  if (!(await titled("Lightcone: Linked by a test")))
    fail(`#scene= link: title ${JSON.stringify(await page.title())}`);

  // 2. A scene file dropped on the page opens; K copies the link of what
  // is open, which carries the dropped file's text unchanged.
  const dropped = retitled("Dropped by a test");
  const drop = async (name, text) =>
    page.evaluate(
      ([name, text]) => {
        const dt = new DataTransfer();
        dt.items.add(new File([text], name, { type: "text/plain" }));
        window.dispatchEvent(new DragEvent("drop", { dataTransfer: dt, bubbles: true, cancelable: true }));
      },
      [name, text],
    );
  await drop("mine.toml", dropped);
  if (!(await titled("Lightcone: Dropped by a test")))
    fail(`dropped file: title ${JSON.stringify(await page.title())}`);
  await page.focus("canvas");
  await page.keyboard.press("KeyK");
  try {
    await page.waitForFunction(() => window.lightconeShareLink !== undefined, null, { timeout: 10_000 });
    const link = await page.evaluate(() => window.lightconeShareLink);
    const back = await page.evaluate((l) => window.unpackLink(l.split("#scene=")[1]), link);
    if (back !== dropped) fail(`share link: carries ${JSON.stringify(back.slice(0, 80))}…`);
    if (!(await page.evaluate(() => location.hash.startsWith("#scene="))))
      fail("share link: not in the address bar");
    console.log(JSON.stringify({ share: link.length + " characters" }));
  } catch {
    fail("K: no share link");
  }
  if (errors.length) fail(`links: console errors: ${JSON.stringify(errors)}`);

  // 3. A bad dropped scene: check's located error in the console (and the
  // scene menu), the game goes on with the scene it had.
  errors.length = 0;
  await drop("bad.toml", dropped.replace(/^size = .*$/m, "size = [2.84, -1.42]"));
  await page.waitForTimeout(1500);
  if (!errors.some((e) => /bad\.toml:\d+:\d+/.test(e)))
    fail(`bad dropped scene: no located error (${JSON.stringify(errors)})`);
  if ((await page.title()) !== "Lightcone: Dropped by a test") fail("bad dropped scene replaced the game");

  // 4. Another file dropped after the share: the address bar no longer
  // carries the shared scene (a reload would bring it back).
  await drop("second.toml", retitled("Second drop"));
  if (!(await titled("Lightcone: Second drop"))) fail(`second drop: title ${JSON.stringify(await page.title())}`);
  if ((await page.evaluate(() => location.hash)) !== "")
    fail("after a second drop the address bar still carries the shared scene");

  // 5. A link cut short: said, and the default scene drawn.
  errors.length = 0;
  await page.goto(base + "#scene=" + data.slice(0, 20));
  await started();
  if (!errors.some((e) => e.includes("cut short")))
    fail(`cut link: no message (${JSON.stringify(errors)})`);
  console.log(JSON.stringify({ links: "checked", messages: errors }));
  await page.close();
}

// The cue by pointer and by touch: a drag from a puck strikes it. The
// pucks of the default scene at 1280×720 (white and red, as drawn in
// docs/web_default.png): the press picks the puck seen within 30 px.
async function cue() {
  const context = await browser.newContext({ viewport: { width: 1280, height: 720 }, hasTouch: true });
  const { page, errors } = await openPage(context);
  await page.goto(base);
  await firstFrame(page);
  await page.waitForTimeout(1000);
  const struck = async (n) =>
    page
      .waitForFunction((n) => window.lightconeStrokes === n, n, { timeout: 10_000 })
      .then(() => page.evaluate(() => window.lightconeStruck), () => null);
  // The mouse: press on white, pull back 90 px, release.
  await page.mouse.move(607, 362);
  await page.mouse.down();
  await page.mouse.move(560, 362, { steps: 4 });
  await page.mouse.move(517, 362, { steps: 4 });
  await page.mouse.up();
  const byMouse = await struck(1);
  if (byMouse !== "white") fail(`mouse drag from white: struck ${byMouse}`);
  // A finger: touch red, pull 80 px, lift.
  const cdp = await context.newCDPSession(page);
  const touch = (type, x, y) =>
    cdp.send("Input.dispatchTouchEvent", { type, touchPoints: type === "touchEnd" ? [] : [{ x, y }] });
  await touch("touchStart", 933, 332);
  for (const x of [953, 973, 993, 1013]) {
    await touch("touchMove", x, 332);
    await page.waitForTimeout(50);
  }
  await touch("touchEnd", 1013, 332);
  const byTouch = await struck(2);
  if (byTouch !== "red") fail(`touch drag from red: struck ${byTouch}`);
  console.log(JSON.stringify({ cue: { mouse: byMouse, touch: byTouch } }));
  if (errors.length) fail(`cue: console errors: ${JSON.stringify(errors)}`);
  await context.close();
}

// The same game: the window's screenshot of the default scene (`lightcone
// play --screenshot` under Xvfb, at 1280×720, paused on its title as the
// page opens it) against the page's. Every pixel is compared but the
// panel's first rows (the page has a *share* button and no lessons in its
// menu): the share of pixels that differ by more than 48 in a channel (the
// two software rasterisers, lavapipe and SwiftShader, edge pixels apart)
// must be under 0.2 % (0.01 % measured: a few edge pixels).
async function parity(nativePath) {
  const fs = await import("node:fs");
  const native = fs.readFileSync(nativePath).toString("base64");
  const page = await browser.newPage();
  await addDecoder(page);
  const result = await page.evaluate(
    async ([a, b]) => {
      const pixels = window.lightconeTestPixels;
      const [p, q] = [await pixels(a), await pixels(b)];
      if (p.w !== q.w || p.h !== q.h) return { size: [p.w, p.h, q.w, q.h] };
      let differ = 0;
      let compared = 0;
      for (let y = 0; y < p.h; y++)
        for (let x = 0; x < p.w; x++) {
          if (x < 328 && y < 70) continue;
          const i = 4 * (y * p.w + x);
          compared++;
          const d = Math.max(
            Math.abs(p.px[i] - q.px[i]),
            Math.abs(p.px[i + 1] - q.px[i + 1]),
            Math.abs(p.px[i + 2] - q.px[i + 2]),
          );
          if (d > 48) differ++;
        }
      return { differ: differ / compared };
    },
    [native, defaultPng.toString("base64")],
  );
  console.log(JSON.stringify({ parity: result }));
  if (result.size) fail(`parity: sizes differ ${JSON.stringify(result.size)}`);
  else if (!(result.differ < 0.002)) fail(`parity: ${(100 * result.differ).toFixed(2)} % of pixels differ`);
  await page.close();
}

// Share on a page with no clipboard (served over http by name, as a school
// would): the link goes to the address bar, the game goes on drawing.
async function shareWithoutClipboard() {
  const { page, errors } = await openPage();
  const url = base.replace("127.0.0.1", "school.test") + "?scene=ten_pucks";
  await page.goto(url);
  await firstFrame(page);
  if (await page.evaluate(() => window.isSecureContext)) fail(`${url}: expected a page without a clipboard`);
  await page.focus("canvas");
  await page.keyboard.press("KeyK");
  const before = await page.evaluate(() => window.lightconeFrames);
  await page.waitForTimeout(1500);
  const after = await page.evaluate(() => window.lightconeFrames);
  const link = await page.evaluate(() => window.lightconeShareLink);
  if (!(after > before)) fail(`share without a clipboard: the game stopped drawing (${before} -> ${after} frames)`);
  if (!link || !link.endsWith("?scene=ten_pucks")) fail(`share without a clipboard: link ${link}`);
  if (errors.length) fail(`share without a clipboard: console errors: ${JSON.stringify(errors)}`);
  console.log(JSON.stringify({ shareWithoutClipboard: { link, frames: after - before } }));
  await page.close();
}

// The same numbers: what the page's first picture shows of each puck of
// ten_pucks at board time 3 s (?at=3, its frame schedule compiled to
// wasm32, optics sequential) against lightcone observe of the native
// build (AVX2 batches, rayon): each centre's emission event to 1e-9 s and
// 1e-9 m.
async function sameNumbers(observedPath) {
  const fs = await import("node:fs");
  const native = JSON.parse(fs.readFileSync(observedPath, "utf8"));
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  await page.goto(base + "?scene=ten_pucks&at=3");
  await page.waitForFunction(() => window.lightconeSeen !== undefined, null, { timeout: 120_000 });
  const seen = JSON.parse(await page.evaluate(() => window.lightconeSeen));
  let worst = { t: 0, x: 0 };
  for (const p of native.pucks) {
    const q = seen.find((s) => s.name === p.name);
    if (!q) {
      fail(`same numbers: ${p.name} not in the page's picture`);
      continue;
    }
    worst.t = Math.max(worst.t, Math.abs(q.t - p.emission.t));
    for (let k = 0; k < 3; k++) worst.x = Math.max(worst.x, Math.abs(q.position[k] - p.emission.position[k]));
  }
  console.log(JSON.stringify({ sameNumbers: { pucks: seen.length, worst } }));
  if (seen.length !== native.pucks.length) fail(`same numbers: ${seen.length} pucks against ${native.pucks.length}`);
  if (!(worst.t <= 1e-9 && worst.x <= 1e-9)) fail(`same numbers: off by ${JSON.stringify(worst)}`);
  await page.close();
}

// WebGPU (`?gpu=webgpu`). In the test's browser, which has no WebGPU
// adapter (Chromium on Linux without flags), the page falls back to
// WebGL2 and draws. In a second browser with SwiftShader's WebGPU, it
// starts on WebGPU (adapter, device) and goes on drawing frames with no
// error. Its pixels are not checked: headless Chromium's screenshots miss
// a WebGPU canvas (even a five-line page clearing one to red), which is
// why WebGPU is not the page's default yet (docs/web.md).
async function webgpu() {
  const drawn = async (page, errors, what) => {
    await page.goto(base + "?gpu=webgpu");
    await firstFrame(page);
    const before = await page.evaluate(() => window.lightconeFrames);
    await page.waitForTimeout(1500);
    const after = await page.evaluate(() => window.lightconeFrames);
    const adapter = await page.evaluate(() => window.lightconeAdapter);
    if (!(after > before)) fail(`${what}: no frames drawn (${before} -> ${after})`);
    if (errors.length) fail(`${what}: console errors: ${JSON.stringify(errors)}`);
    return { adapter, frames: after - before };
  };
  const plain = await openPage();
  const fallback = await drawn(plain.page, plain.errors, "?gpu=webgpu without WebGPU");
  // (Should a Chromium give an adapter without flags, WebGPU is right.)
  const hasAdapter = await plain.page.evaluate(async () => !!(navigator.gpu && (await navigator.gpu.requestAdapter())));
  const expected = hasAdapter ? /\(BrowserWebGpu\)$/ : /\(Gl\)$/;
  if (!expected.test(fallback.adapter)) fail(`?gpu=webgpu (adapter: ${hasAdapter}): drew with ${fallback.adapter}`);
  await plain.page.close();
  const gpuBrowser = await launch([
    "--enable-unsafe-webgpu",
    "--enable-features=Vulkan,WebGPU",
    "--use-webgpu-adapter=swiftshader",
  ]);
  try {
    const context = await gpuBrowser.newContext({ viewport: { width: 1280, height: 720 } });
    const withGpu = await openPage(context);
    const webgpuRun = await drawn(withGpu.page, withGpu.errors, "?gpu=webgpu with WebGPU");
    if (!/\(BrowserWebGpu\)$/.test(webgpuRun.adapter)) fail(`?gpu=webgpu with WebGPU: drew with ${webgpuRun.adapter}`);
    console.log(JSON.stringify({ webgpu: { fallback, webgpu: webgpuRun } }));
  } catch (e) {
    fail(`?gpu=webgpu with WebGPU: ${e.message}`);
  } finally {
    await gpuBrowser.close();
  }
}

// The effects seen in the page as in the window (issue 32): the
// contraction scene at board time 1 s (?at=1 publishes the frame's layout,
// `window.lightconeLayout`, the sidecar `play --screenshot` writes) within
// 10 s of the first frame: the magnifier's moving body at least 60 px
// across, its measured length / width on the page's own pixels within 5 %
// of 1/γ (as tests/view.rs measures the window's), and the clocks: the
// moving puck's proper time 1/γ of the resting one's. Then the flyby (an
// eye passing the table at β = 0.85) screenshotted. Pictures beside SHOT.
async function effects() {
  const { page, errors } = await openPage();
  await page.goto(base + "?scene=contraction&at=1");
  await firstFrame(page);
  const t0 = Date.now();
  const handle = await page
    .waitForFunction(
      () => {
        const l = window.lightconeLayout && JSON.parse(window.lightconeLayout);
        return l && l.magnifier ? window.lightconeLayout : null;
      },
      null,
      { timeout: 10_000 },
    )
    .catch(() => null);
  if (!handle) {
    fail(`?scene=contraction: no magnifier within 10 s of the first frame (${JSON.stringify(errors)})`);
    await page.close();
    return;
  }
  const seenMs = Date.now() - t0;
  const layout = JSON.parse(await handle.jsonValue());
  await page.waitForTimeout(500);
  const box = await page.evaluate(() => {
    const r = document.querySelector("canvas").getBoundingClientRect();
    return { x: r.x, y: r.y, w: r.width, h: r.height, dpr: window.devicePixelRatio };
  });
  const png = await page.screenshot({ path: shot.replace(/\.png$/, "_contraction.png") });
  await addDecoder(page);
  const m = layout.magnifier;
  const measured = await page.evaluate(
    async ([data, m, box]) => {
      const { w, px } = await window.lightconeTestPixels(data);
      // The layout is in the canvas's physical pixels, the screenshot in
      // the device's: the canvas's place (CSS px) times the pixel ratio.
      const [bx, by, bw, bh] = m.body;
      const [ox, oy] = [box.x * box.dpr, box.y * box.dpr];
      let [x0, x1, y0, y1] = [Infinity, -1, Infinity, -1];
      for (let y = Math.floor(oy + by); y < oy + by + bh; y++) {
        for (let x = Math.floor(ox + bx); x < ox + bx + bw; x++) {
          const i = 4 * (y * w + x);
          if ([0, 1, 2].every((k) => Math.abs(px[i + k] - m.colour[k]) <= 24)) {
            x0 = Math.min(x0, x);
            x1 = Math.max(x1, x);
            y0 = Math.min(y0, y);
            y1 = Math.max(y1, y);
          }
        }
      }
      return { length: x1 - x0 + 1, width: y1 - y0 + 1 };
    },
    [png.toString("base64"), m, box],
  );
  const clock = (name) => (layout.pucks.find((p) => p.name === name) || {}).clock_s;
  const [moving, resting] = [clock("moving"), clock("resting")];
  const aspect = measured.length / measured.width;
  console.log(JSON.stringify({ contraction: { seenMs, gamma: m.gamma, measured, aspect, clocks: { moving, resting }, box } }));
  if (m.puck !== "moving") fail(`contraction: the magnifier shows ${m.puck}`);
  if (!(Math.max(measured.length, measured.width) >= 60)) fail(`contraction: the body is ${JSON.stringify(measured)} px`);
  if (!(Math.abs(aspect * m.gamma - 1) < 0.05)) fail(`contraction: length / width ${aspect} against 1/γ ${1 / m.gamma}`);
  if (!(Math.abs(moving - resting / m.gamma) < 1e-3 * resting))
    fail(`contraction: clocks moving ${moving} s, resting ${resting} s, γ ${m.gamma}`);
  if (errors.length) fail(`contraction: console errors: ${JSON.stringify(errors)}`);
  await page.close();

  const flyby = await openPage();
  await flyby.page.goto(base + "?scene=flyby&at=1.5");
  await firstFrame(flyby.page);
  await flyby.page.waitForFunction(() => window.lightconeLayout !== undefined, null, { timeout: 10_000 });
  await flyby.page.waitForTimeout(500);
  await flyby.page.screenshot({ path: shot.replace(/\.png$/, "_flyby.png") });
  if (flyby.errors.length) fail(`flyby: console errors: ${JSON.stringify(flyby.errors)}`);
  await flyby.page.close();
}

await check("", shot);
await check("?scene=ten_pucks", shot.replace(/\.png$/, "_ten_pucks.png"));
await effects();
await links();
await shareWithoutClipboard();
await cue();
if (process.env.NATIVE_OBSERVE) await sameNumbers(process.env.NATIVE_OBSERVE);
else console.log("same numbers as observe: skipped (no NATIVE_OBSERVE)");
if (process.env.NATIVE_PNG && defaultPng) await parity(process.env.NATIVE_PNG);
else console.log("parity with the window: skipped (no NATIVE_PNG)");
// Last: a failure starting WebGPU must not keep the checks above from
// running.
await webgpu();
await browser.close();
process.exit(failed ? 1 : 0);
