// The browser's lessons against the desktop's: every shipped lesson runs
// in the page (its Python in Pyodide in the lesson's Web Worker, its world
// answered by the game in wasm), played with nobody at the page
// (`?drive=30`: as `lightcone lesson --fps 30` plays it), and its claims
// (text, held or not, and the numbers behind them) and closing message
// must equal what `lightcone lesson --json` gives on the desktop. Then a
// lesson carried in a `#lesson=` link runs, one with a bug shows its
// traceback in the panel while the game goes on, and a screenshot of a
// lesson's panel is saved.
//
//   NATIVE_LESSONS=outcomes.json node web/tests/lessons.mjs URL SCREENSHOT.png
//
// `outcomes.json`: {"NAME.py": <lightcone lesson NAME.py --json>, ...}.
// Prints one JSON line per lesson (seconds it took in the page) and exits
// 1 on any failure.
import { readFileSync } from "node:fs";
import { chromium } from "playwright-core";

const [base, shot] = process.argv.slice(2);
const native = JSON.parse(readFileSync(process.env.NATIVE_LESSONS, "utf8"));
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist", "--no-sandbox"],
});

let failed = false;
function fail(what) {
  console.error(`FAIL ${what}`);
  failed = true;
}

async function openPage(url, viewport) {
  const page = await browser.newPage({ viewport });
  const errors = [];
  page.on("pageerror", (e) => errors.push(`uncaught: ${e.message}`));
  await page.goto(url);
  return { page, errors };
}

// The page's lesson state (`window.lightconeLessonState`) once `done(state)`
// holds, or null after `seconds`.
async function lessonState(page, done, seconds) {
  const until = Date.now() + seconds * 1000;
  while (Date.now() < until) {
    const text = await page.evaluate(() => window.lightconeLessonState || null);
    if (text) {
      const state = JSON.parse(text);
      if (done(state)) return state;
    }
    await page.waitForTimeout(250);
  }
  return null;
}

const ended = (s) => s.closing !== null || s.error !== null;

// Lessons whose numbers cannot match the desktop's to the last digit: the
// gas's 120 pucks start in directions from the lesson's own
// `math.cos`/`math.sin`, which differ by an ulp between Pyodide's libm
// (musl) and the desktop's (glibc), and a gas is chaotic: after 6 000
// collisions the two runs are different gases. Their claims must say the
// same and hold in both; the numbers behind them are printed, not
// compared.
const CHAOTIC = new Set(["gas.py"]);

// 1. Every shipped lesson gives the desktop's claims.
for (const [name, theirs] of Object.entries(native).filter(([n]) => !process.env.ONLY || n === process.env.ONLY)) {
  const started = Date.now();
  // A small page: software WebGL draws it faster (the lesson is the test).
  const { page, errors } = await openPage(`${base}?lesson=${name}&drive=30`, { width: 640, height: 400 });
  const state = await lessonState(page, ended, 300);
  const seconds = (Date.now() - started) / 1000;
  console.log(JSON.stringify({ lesson: name, seconds: Number(seconds.toFixed(1)) }));
  if (!state) {
    fail(`${name}: did not finish in the page within 300 s`);
  } else if (state.error !== null) {
    fail(`${name}: stopped in the page: ${state.error}`);
  } else {
    const keep = CHAOTIC.has(name) ? (c) => ({ claim: c.claim, ok: c.ok }) : (c) => ({ claim: c.claim, detail: c.detail, ok: c.ok });
    const ours = JSON.stringify(state.claims.map(keep));
    const desktop = JSON.stringify(theirs.claims.map(keep));
    if (ours !== desktop) fail(`${name}: claims differ\n  page:    ${ours}\n  desktop: ${desktop}`);
    if (!state.claims.every((c) => c.ok)) fail(`${name}: a claim failed in the page: ${JSON.stringify(state.claims)}`);
    if (CHAOTIC.has(name))
      console.log(JSON.stringify({ lesson: name, page: state.claims.map((c) => c.detail), desktop: theirs.claims.map((c) => c.detail) }));
    if (state.finished !== theirs.finished) fail(`${name}: closes ${JSON.stringify(state.finished)}, desktop ${JSON.stringify(theirs.finished)}`);
  }
  if (errors.length) fail(`${name}: ${JSON.stringify(errors)}`);
  await page.close();
}

// The link's DATA of `text`, as game/src/links.rs writes it (raw DEFLATE,
// base64url), made by the browser's own CompressionStream.
async function pack(page, text) {
  return page.evaluate(async (t) => {
    const s = new Blob([t]).stream().pipeThrough(new CompressionStream("deflate-raw"));
    const bytes = new Uint8Array(await new Response(s).arrayBuffer());
    let bin = "";
    for (const b of bytes) bin += String.fromCharCode(b);
    return btoa(bin).replaceAll("+", "-").replaceAll("/", "_").replace(/=+$/, "");
  }, text);
}

// 2. A teacher's lesson carried in the link, and 3. one that raises.
const mine = `import lightcone

def setup(world):
    s = lightcone.Scene(title="A link's lesson")
    s.add_puck("a", (0.5, 0.71), u=(0.8, 0.0))
    world.start(s)
    world.say("carried by the link")

def on_frame(world, t):
    if t > 0.5 and not world.finished:
        world.check("the puck moves", world.velocity("a")[0] > 0.7, f"u = {world.velocity('a')[0]:.3f}")
        world.finish("done")
`;
const broken = mine.replace('world.say("carried by the link")', 'world.say("about to fail")\n    1 / 0');
{
  const { page, errors } = await openPage(base, { width: 1280, height: 720 });
  await page.waitForFunction(() => window.lightconeFrames > 0, null, { timeout: 60000 });
  const data = await pack(page, mine);
  const bad = await pack(page, broken);
  await page.goto(`${base}?drive=30#lesson=${data}`);
  const state = await lessonState(page, ended, 120);
  if (!state || state.closing !== "done" || state.claims.length !== 1 || !state.claims[0].ok)
    fail(`#lesson= link: ${JSON.stringify(state)}`);
  // Another query: a new page (the same one with another fragment would
  // reload itself on `hashchange`).
  await page.goto(`${base}?broken#lesson=${bad}`);
  const failedState = await lessonState(page, (s) => s.error !== null, 120);
  if (!failedState || !failedState.error.includes("ZeroDivisionError") || !failedState.error.includes("line 8"))
    fail(`a lesson that raises: ${JSON.stringify(failedState)}`);
  const frames = await page.evaluate(() => window.lightconeFrames);
  await page.waitForTimeout(1000);
  if (!((await page.evaluate(() => window.lightconeFrames)) > frames)) fail("a lesson that raises: the game stopped drawing");
  if (errors.length) fail(`links: ${JSON.stringify(errors)}`);
  await page.close();
}

// 4. A lesson's panel, for docs/: a shipped lesson waiting for the
// student's prediction.
{
  const { page } = await openPage(`${base}?lesson=collision_angle`, { width: 1280, height: 720 });
  const state = await lessonState(page, (s) => s.question !== null || s.error !== null, 120);
  if (!state || state.error) fail(`collision_angle in the page: ${JSON.stringify(state)}`);
  await page.waitForTimeout(1500);
  await page.screenshot({ path: shot });
  await page.close();
}

await browser.close();
process.exit(failed ? 1 : 0);
