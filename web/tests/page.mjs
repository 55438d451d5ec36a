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

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  args: [
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--ignore-gpu-blocklist",
    "--no-sandbox",
  ],
});

let failed = false;
function fail(what) {
  console.error(`FAIL ${what}`);
  failed = true;
}

async function check(query, screenshot) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  const errors = [];
  page.on("console", (m) => {
    if (m.type() === "error") errors.push(m.text());
  });
  page.on("pageerror", (e) => errors.push(`uncaught: ${e.message}`));
  const url = base + query;
  await page.goto(url);
  try {
    await page.waitForFunction(() => window.lightconeFirstFrameMs !== undefined, null, {
      timeout: 120_000,
    });
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
  // The screenshot's pixels, read back by the page itself (no PNG decoder
  // needed here): distinct colours (4 bits a channel) and the share of
  // the commonest one.
  const stats = await page.evaluate(async (data) => {
    const img = new Image();
    img.src = "data:image/png;base64," + data;
    await img.decode();
    const c = document.createElement("canvas");
    c.width = img.width;
    c.height = img.height;
    const ctx = c.getContext("2d");
    ctx.drawImage(img, 0, 0);
    const px = ctx.getImageData(0, 0, c.width, c.height).data;
    const counts = new Map();
    for (let i = 0; i < px.length; i += 4) {
      const k = ((px[i] >> 4) << 8) | ((px[i + 1] >> 4) << 4) | (px[i + 2] >> 4);
      counts.set(k, (counts.get(k) || 0) + 1);
    }
    const top = Math.max(...counts.values());
    return { colours: counts.size, commonest: top / (px.length / 4) };
  }, png.toString("base64"));
  console.log(JSON.stringify({ url, firstFrameMs, ...stats, errors }));
  if (errors.length) fail(`${url}: console errors: ${JSON.stringify(errors)}`);
  if (stats.colours < 16 || stats.commonest > 0.95)
    fail(`${url}: the page looks blank (${stats.colours} colours, commonest ${stats.commonest})`);
  await page.close();
}

await check("", shot);
await check("?scene=ten_pucks", shot.replace(/\.png$/, "_ten_pucks.png"));
await browser.close();
process.exit(failed ? 1 : 0);
