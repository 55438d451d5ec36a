// The page's frame rate in Debian's headless Chromium on software WebGL2
// (SwiftShader): for each case, the mean interval between animation
// frames (the game draws once a frame) over 5 s of the game running,
// after its first frame and 1.5 s more. Not a test: the figures of
// BENCHMARKS.md ("Frame rate on a software rasteriser").
//
//   node web/tests/frame_rate.mjs ROUNDS CASE... 
//
// CASE is `URL@WIDTHxHEIGHT`, e.g. `http://127.0.0.1:8000/?scene=ten_pucks@1280x720`;
// cases are run in turn, ROUNDS times over. Prints each case's intervals
// (ms), sorted.
import { chromium } from "playwright-core";

const [rounds, ...cases] = process.argv.slice(2);
if (!(rounds > 0) || !cases.length) {
  console.error("usage: node frame_rate.mjs ROUNDS URL@WIDTHxHEIGHT...");
  process.exit(2);
}
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist", "--no-sandbox"],
});
const intervals = {};
for (let r = 0; r < rounds; r++) {
  for (const c of cases) {
    const at = c.lastIndexOf("@");
    const [w, h] = c.slice(at + 1).split("x").map(Number);
    const page = await browser.newPage({ viewport: { width: w, height: h } });
    await page.goto(c.slice(0, at));
    await page.waitForFunction(() => window.lightconeFirstFrameMs !== undefined, null, { timeout: 120_000 });
    await page.waitForTimeout(1500);
    await page.focus("canvas");
    await page.keyboard.press("Space"); // start the game
    await page.waitForTimeout(300);
    const mean = await page.evaluate(
      () =>
        new Promise((done) => {
          let n = 0;
          const t0 = performance.now();
          const tick = (now) => {
            n++;
            if (now - t0 < 5000) requestAnimationFrame(tick);
            else done((now - t0) / n);
          };
          requestAnimationFrame(tick);
        }),
    );
    (intervals[c] ||= []).push(Math.round(mean * 10) / 10);
    await page.close();
  }
}
for (const [c, v] of Object.entries(intervals)) console.log(c, JSON.stringify(v.sort((a, b) => a - b)));
await browser.close();
