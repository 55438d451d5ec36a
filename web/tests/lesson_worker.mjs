// The browser's lesson worker, tested without the game: serves web/dist/
// (built by scripts/web.sh) on a local port, opens a blank page that loads
// lesson_host.js, and plays the game's part of the lesson protocol
// (game/src/lesson/remote.rs) by hand through `window.lightconeLesson`:
// opens lessons (their source here), sends calls, answers each request
// with canned replies, and checks the request lines and Done messages.
// The worker runs Pyodide with the real `lightcone` package and the real
// engine module (web-engine/).
//
//   node web/tests/lesson_worker.mjs [DIST]
//
// Checked: the requests a setup makes and their answers (a scene built
// and started, an error answer raised as its class), the Done messages
// (printed lines, hooks, tracebacks "in HOOK:" at the lesson's line), the
// engine's Scene and Simulation against the extension's answers, a lesson
// without setup or that does not compile, a hook past its limit stopped
// with TimeoutError at its line (even one that catches it), a hanging hook
// stopped by the page, a
// browser without JSPI told so, nothing fetched from another host.
// Prints JSON lines (ms from open to "ready", a request's round trip, the
// Pyodide files fetched), then "N passed, N failed"; exits 1 on any
// failure. Debian's Chromium, headless.
import { createReadStream, existsSync, readFileSync, statSync } from "node:fs";
import { createServer } from "node:http";
import { extname, join, normalize, dirname } from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";

const here = dirname(fileURLToPath(import.meta.url));
const dist = process.argv[2] || join(here, "..", "dist");
for (const f of ["lesson_host.js", "lesson_worker.js", "lightcone_engine_web.js", "pyodide/pyodide.mjs", "python/lightcone_web_child.py"]) {
  if (!existsSync(join(dist, f))) {
    console.error(`${dist}/${f} missing: run scripts/web.sh`);
    process.exit(2);
  }
}

// ---- The server: web/dist/ and a blank page.

const TYPES = {
  ".html": "text/html",
  ".js": "text/javascript",
  ".mjs": "text/javascript",
  ".wasm": "application/wasm",
  ".json": "application/json",
  ".zip": "application/zip",
  ".py": "text/x-python",
};
const PAGE = `<!doctype html><meta charset="utf-8"><title>lesson worker test</title><link rel="icon" href="data:,">
<script src="./lesson_host.js"></script>`;
// The same page with the game's coi.js first (index.html's order).
const COI_PAGE = PAGE.replace("<script", '<script src="./coi.js"></script>\n<script');
const fetched = [];
// Under /nojspi/, the same files, but a worker that finds no JSPI (as in
// a browser without it: Chromium here cannot turn it off).
const NO_JSPI = "delete WebAssembly.Suspending; delete WebAssembly.Suspender; delete WebAssembly.promising;\n";
// Under /nojspi-coi/, the same without JSPI, every response with the
// headers that make a page cross-origin isolated (a server that sends
// them); under /nojspi-sw/, without JSPI in the page too (its coi.js) and
// without the headers, which coi_sw.js then adds (python3 -m http.server).
const ISOLATED = { "cross-origin-opener-policy": "same-origin", "cross-origin-embedder-policy": "require-corp" };
const server = createServer((req, res) => {
  let path = decodeURIComponent(new URL(req.url, "http://x").pathname);
  const prefix = ["/nojspi/", "/nojspi-coi/", "/nojspi-sw/"].find((p) => path.startsWith(p));
  if (prefix) path = path.slice(prefix.length - 1);
  const headers = prefix === "/nojspi-coi/" ? ISOLATED : {};
  if (prefix && (path === "/lesson_worker.js" || (prefix === "/nojspi-sw/" && path === "/coi.js"))) {
    res.writeHead(200, { "content-type": "text/javascript", ...headers });
    return res.end(NO_JSPI + readFileSync(join(dist, path), "utf8"));
  }
  if (path === "/__lesson_test.html" || path === "/__coi_test.html") {
    res.writeHead(200, { "content-type": "text/html", ...headers });
    return res.end(path === "/__coi_test.html" ? COI_PAGE : PAGE);
  }
  const file = normalize(join(dist, path));
  if (!file.startsWith(normalize(dist))) {
    res.writeHead(403);
    return res.end();
  }
  if (!existsSync(file) || !statSync(file).isFile()) {
    fetched.push(`${path} (404)`);
    res.writeHead(404);
    return res.end();
  }
  fetched.push(path);
  res.writeHead(200, { "content-type": TYPES[extname(file)] || "application/octet-stream", ...headers });
  createReadStream(file).pipe(res);
});
await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));
const origin = `http://127.0.0.1:${server.address().port}`;

// ---- The browser, and the game's side of the protocol.

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  args: ["--no-sandbox"],
});
let failed = 0;
let passed = 0;
function fail(what) {
  console.error(`FAIL ${what}`);
  failed += 1;
}
function check(ok, what) {
  if (ok) passed += 1;
  else fail(what);
  return ok;
}

let page = await browser.newPage();
const consoleLines = [];
page.on("console", (m) => consoleLines.push(`${m.type()}: ${m.text()}`));
page.on("pageerror", (e) => fail(`uncaught in the page: ${e.message}`));
// Nothing may come from another host.
await page.context().route("**/*", (route) => {
  const url = route.request().url();
  if (url.startsWith(origin + "/") || url.startsWith("data:") || url.startsWith("blob:")) return route.continue();
  fail(`a request to another host: ${url}`);
  return route.abort();
});
await page.goto(`${origin}/__lesson_test.html`);

// The page keeps what `take()` gives, with when each arrived (ms on its
// clock), so the test reads messages one at a time.
const prepare = (p) => p.evaluate(() => {
  const queue = [];
  setInterval(() => {
    for (const m of window.lightconeLesson.take()) queue.push({ ...m, at: performance.now() });
  }, 2);
  window.__next = (ms) =>
    new Promise((resolve) => {
      const until = performance.now() + ms;
      const poll = () => {
        if (queue.length) return resolve(queue.shift());
        if (performance.now() > until) return resolve(null);
        setTimeout(poll, 2);
      };
      poll();
    });
  window.__now = () => performance.now();
});
await prepare(page);
const next = (ms = 20_000) => page.evaluate((ms) => window.__next(ms), ms);
const lesson = {
  open: (name, source, limit = 10) => page.evaluate(([n, s, l]) => window.lightconeLesson.open(n, s, l), [name, source, limit]),
  send: (line) => page.evaluate((l) => window.lightconeLesson.send(l), line),
  state: () => page.evaluate(() => window.lightconeLesson.state()),
  stop: () => page.evaluate(() => window.lightconeLesson.stop()),
};

// The next message, which must be an Up line: parsed.
async function up(what) {
  const m = await next();
  if (!check(m && m.kind === "line", `${what}: expected a line, got ${JSON.stringify(m)}`)) return null;
  return JSON.parse(m.line);
}

// The next message must be the request `op`; returns its args.
async function request(op, what) {
  const m = await up(what);
  if (!m) return null;
  if (!check(m.request && m.request.op === op, `${what}: expected request ${op}, got ${JSON.stringify(m)}`)) return null;
  return m.request;
}

// The next message must be a Done line: returns its fields.
async function done(what, timedOut = false) {
  const m = await up(what);
  if (!m) return null;
  if (!check(m.done, `${what}: expected done, got ${JSON.stringify(m)}`)) return null;
  check(
    JSON.stringify(Object.keys(m.done)) === JSON.stringify(["error", "timed_out", "printed", "hooks"]),
    `${what}: Done's fields ${JSON.stringify(Object.keys(m.done))}`,
  );
  check(m.done.timed_out === timedOut, `${what}: timed_out ${m.done.timed_out}`);
  return m.done;
}

// Opens a lesson and waits for "ready"; ms from open to ready.
async function openReady(name, source, limit = 10) {
  const t0 = await page.evaluate(() => window.__now());
  await lesson.open(name, source, limit);
  check((await lesson.state()) === "loading", `${name}: state after open`);
  const m = await next(120_000);
  if (!check(m && m.kind === "ready", `${name}: expected ready, got ${JSON.stringify(m)}`)) return null;
  check((await lesson.state()) === "ready", `${name}: state after ready`);
  console.log(JSON.stringify({ lesson: name, ready_ms: Math.round(m.at - t0) }));
  return m.at - t0;
}

const NO_GAME =
  "the world has no game here: call world.start(scene) in setup(world), and use the world only inside a hook";
const NONE = JSON.stringify({ $none: NO_GAME });
// As serde writes the game's snapshot (floats with their ".0").
const SNAPSHOT =
  '{"t":0.0,"c":1.42,"paused":false,"time_scale":1.0,"view":"seen","observer":null,' +
  '"effects":{"contraction":true,"light_delay":true,"aberration":true,"doppler":true,"searchlight":true,"time_dilation":true}}';
// A call line; `args` as JSON text (as serde writes them: 2.0, not 2).
const call = (hook, args, snapshot = SNAPSHOT) => `{"call":${JSON.stringify(hook)},"args":${args},"snapshot":${snapshot}}`;

// ---- A lesson: setup builds a scene, starts it, asks the game.

const REQUESTS = 200;
const TWO_PUCKS = `"""A test lesson: two pucks."""
import lightcone

REQUESTS = ${REQUESTS}


def setup(world):
    scene = lightcone.Scene(title="Two pucks")
    scene.add_puck("a", (0.5, 0.71), beta=(0.6, 0.0))
    scene.add_puck("b", (2.0, 0.71))
    assert scene.pucks == ["a", "b"], scene.pucks
    try:
        world.t
    except RuntimeError as e:
        print("before start:", e)
    world.start(scene)
    world.say("Two pucks meet.")
    print("t =", world.t, "c =", world.c)
    u = world.velocity("a")
    print("u(a) =", u, type(u).__name__)
    try:
        world.velocity("zz")
    except KeyError as e:
        print("KeyError:", e)
    sim = lightcone.Simulation(scene)
    sim.run_until(0.5)
    print("sim:", float(sim.time), tuple(float(round(x, 9)) for x in sim.velocity("a")))
    try:
        scene.add_puck("c", (1.0, 0.3), beta=(1.2, 0.0))
    except lightcone.SpeedOfLightError as e:
        print("refused:", type(e).__name__, isinstance(e, lightcone.SceneError))
    print(isinstance(world, lightcone.World), lightcone.__version__ != "")


def on_frame(world, t):
    if t > 1.0:
        raise ValueError(f"too late: t = {t}")
    if t == 0.0:
        for i in range(REQUESTS):
            world.say(str(i))
        return
    world.paused = True


def on_collision(world, event):
    for i in range(100):
        print("line", i)
    print("x" * 5000)


def on_answer(world, question, chosen):
    lightcone.Scene().add_puck("x", (1.0, 1.0), beta=(2.0, 0.0))
`;

const readyMs = await openReady("lessons/two_pucks.py", TWO_PUCKS);
console.log(JSON.stringify({ lesson_worker_ready_ms: readyMs && Math.round(readyMs) }));

if (readyMs !== null) {
  const t0 = await page.evaluate(() => window.__now());
  await lesson.send(call("setup", "[]", NONE));
  const start = await request("start", "setup");
  if (start) {
    check(start.args.length === 1 && typeof start.args[0].$scene === "string", `start's args ${JSON.stringify(start.args)}`);
    const pucks = JSON.parse(start.args[0].$scene).pucks.map((p) => p.name);
    check(JSON.stringify(pucks) === '["a","b"]', `the started scene's pucks ${JSON.stringify(pucks)}`);
    check(JSON.stringify(start.kwargs) === "{}", `start's kwargs ${JSON.stringify(start.kwargs)}`);
  }
  await lesson.send(`{"ok":null,"snapshot":${SNAPSHOT}}`);
  const say = await request("say", "setup");
  check(say && JSON.stringify(say.args) === '["Two pucks meet."]', `say's args ${JSON.stringify(say && say.args)}`);
  await lesson.send(`{"ok":null,"snapshot":${SNAPSHOT}}`);
  const velocity = await request("velocity", "setup");
  check(velocity && JSON.stringify(velocity.args) === '["a"]', `velocity's args ${JSON.stringify(velocity && velocity.args)}`);
  await lesson.send(`{"ok":[0.75,0.0],"snapshot":${SNAPSHOT}}`);
  await request("velocity", "setup (a puck the scene lacks)");
  await lesson.send(`{"error":["KeyError","no puck named \\"zz\\"; the scene has [\\"a\\", \\"b\\"]"],"snapshot":${SNAPSHOT}}`);
  const setup = await done("setup");
  const t1 = await page.evaluate(() => window.__now());
  console.log(JSON.stringify({ lesson_setup_ms: Math.round(t1 - t0) }));
  if (setup) {
    check(setup.error === null, `setup's error: ${setup.error}`);
    check(JSON.stringify(setup.hooks) === '["on_frame","on_collision","on_answer"]', `setup's hooks ${JSON.stringify(setup.hooks)}`);
    const expected = [
      `before start: ${NO_GAME}`,
      "t = 0.0 c = 1.42",
      "u(a) = (0.75, 0.0) tuple",
      `KeyError: 'no puck named "zz"; the scene has ["a", "b"]'`,
      "sim: 0.5 (0.75, 0.0)",
      "refused: SpeedOfLightError True",
      "True True",
    ];
    check(JSON.stringify(setup.printed) === JSON.stringify(expected), `setup printed ${JSON.stringify(setup.printed, null, 1)}`);
  }

  // A hook that sets an attribute (a request), and one that raises.
  await lesson.send(call("on_frame", "[0.5]"));
  const paused = await request("=paused", "on_frame");
  check(paused && JSON.stringify(paused.args) === "[true]", `=paused's args ${JSON.stringify(paused && paused.args)}`);
  await lesson.send(`{"ok":null,"snapshot":${SNAPSHOT.replace('"paused":false', '"paused":true')}}`);
  const frame = await done("on_frame");
  check(frame && frame.error === null && frame.hooks.length === 0, `on_frame: ${JSON.stringify(frame)}`);

  await lesson.send(call("on_frame", "[2.0]"));
  const raised = await done("on_frame (raising)");
  if (raised) {
    const e = raised.error || "";
    check(e.startsWith("in on_frame:\nTraceback (most recent call last):\n"), `on_frame's error starts: ${e}`);
    const line = TWO_PUCKS.split("\n").findIndex((l) => l.includes("raise ValueError")) + 1;
    check(e.includes(`File "lessons/two_pucks.py", line ${line}, in on_frame\n`), `on_frame's error names line ${line}: ${e}`);
    check(e.endsWith("ValueError: too late: t = 2.0"), `on_frame's error ends: ${e}`);
    check(!e.includes("lightcone_web_child"), `on_frame's error shows the worker's own frames: ${e}`);
  }

  // Many requests in one hook, each answered as soon as it is taken.
  const served = await page.evaluate(
    async ([line, reply, n]) => {
      const t0 = performance.now();
      window.lightconeLesson.send(line);
      let answered = 0;
      for (;;) {
        const m = await window.__next(20_000);
        if (!m || m.kind !== "line") return { error: JSON.stringify(m) };
        if (JSON.parse(m.line).done) return { answered, ms: performance.now() - t0, done: JSON.parse(m.line).done };
        answered += 1;
        window.lightconeLesson.send(reply);
      }
    },
    [call("on_frame", "[0.0]"), `{"ok":null,"snapshot":${SNAPSHOT}}`, REQUESTS],
  );
  check(served.answered === REQUESTS && served.done && served.done.error === null, `requests: ${JSON.stringify(served)}`);

  // What a hook printed: the last 40 lines, each at most 4096 characters.
  await lesson.send(call("on_collision", '[{"t":1.0}]'));
  const printed = await done("on_collision");
  if (printed) {
    check(printed.printed.length === 40, `on_collision printed ${printed.printed.length} lines`);
    check(printed.printed[0] === "line 61", `on_collision's first kept line: ${printed.printed[0]}`);
    check(printed.printed[39] === "x".repeat(4096) + "…", `on_collision's long line: ${printed.printed[39].length} characters`);
  }

  // An engine error in a hook: raised as the extension's class, and no
  // frame of the stand-in in the traceback.
  await lesson.send(call("on_answer", '["Which?",1]'));
  const refused = await done("on_answer");
  if (refused) {
    const e = refused.error || "";
    check(e.startsWith("in on_answer:\nTraceback (most recent call last):\n"), `on_answer's error starts: ${e}`);
    check(/\n_lightcone\.SpeedOfLightError: .+$/.test(e), `on_answer's error ends: ${e}`);
    check(!e.includes("_lightcone.py"), `on_answer's error shows the stand-in's frames: ${e}`);
  }
}

// ---- The engine's Scene and Simulation through the stand-in: the lesson
// asserts what the extension would answer.

const ENGINE = `import os
import lightcone

PAPER = ${JSON.stringify(readFileSync(join(here, "..", "..", "assets", "scenes", "paper_carom.toml"), "utf8"))}


def raises(cls, f, *args, **kwargs):
    try:
        f(*args, **kwargs)
    except cls as e:
        return type(e).__name__, str(e)
    raise AssertionError(f"{f.__name__}{args}{kwargs} did not raise {cls.__name__}")


def setup(world):
    s = lightcone.Scene(title="Engine")
    s.add_puck("a", (0.5, 0.71), beta=(0.6, 0.0))
    s.add_puck("b", (2.0, 0.71), color="red")
    s.add_observer("eye", (1.42, 0.71, 2.0))
    s.set_effect("doppler", False)
    assert repr(s).startswith('Scene("Engine", 2 pucks'), repr(s)
    assert (s.pucks, s.observers, s.title) == (["a", "b"], ["eye"], "Engine")
    assert s.effects["doppler"] is False and s.effects["contraction"] is True, s.effects
    assert abs(s.c - 1.42) < 1e-12 and s.friction == 0.0, (s.c, s.friction)
    rough = lightcone.Scene._from_json(s._to_json())
    rough.friction = 0.1
    assert (rough.friction, s.friction) == (0.1, 0.0)
    assert raises(lightcone.SceneError, setattr, rough, "c", -1.0)[0] == "OutOfRangeError"
    assert raises(lightcone.SceneError, lightcone.Scene, size=(-1.0, 1.0))[0] == "OutOfRangeError"
    assert raises(lightcone.SpeedOfLightError, s.add_puck, "c", (1.0, 0.3), beta=(1.2, 0.0))
    assert raises(lightcone.OverlapError, s.add_puck, "d", (0.51, 0.71))
    assert raises(ValueError, s.set_effect, "sparkle", True)
    assert raises(TypeError, s.add_puck, "e")
    assert s.pucks == ["a", "b"], s.pucks
    paper = lightcone.Scene.from_toml(PAPER, "paper_carom.toml")
    assert paper.title.startswith("Carom"), paper.title
    with open("/tmp/paper.toml", "w") as f:
        f.write(PAPER)
    assert lightcone.Scene.load("/tmp/paper.toml").pucks == paper.pucks
    kind, message = raises(lightcone.SceneError, lightcone.Scene.load, "/tmp/missing.toml")
    assert message.startswith("/tmp/missing.toml: cannot read: "), message
    kind, message = raises(lightcone.SceneError, lightcone.Scene.from_toml, "title = 3", "bad.toml")
    assert message.startswith("bad.toml:1:"), message

    sim = lightcone.Simulation(s)
    sim.run_until(3.0)
    assert sim.time == 3.0, sim.time
    collisions = sim.collisions()
    assert collisions and isinstance(collisions[0], lightcone.Collision), collisions
    assert collisions[0].kind == "puck_puck", collisions[0]
    state = sim.state()
    assert isinstance(state, lightcone.State) and [p.name for p in state.pucks] == ["a", "b"]
    assert isinstance(sim.observe("eye"), lightcone.Observation)
    assert raises(lightcone.NotComputedError, sim.observe, at=100.0)
    assert raises(KeyError, sim.velocity, "zz")
    sim.impulse("b", (0.1, 0.0))
    assert isinstance(sim.velocity("b"), tuple)
    sim.step(0.5)
    assert sim.time == 3.5, sim.time
    frame = sim.diagram("/tmp/diagram.png", size=(200, 140), frame="a")
    assert isinstance(frame, lightcone.Frame) and (frame.width, frame.height) == (200, 140)
    assert frame.png[:4] == b"\\x89PNG" and os.path.getsize("/tmp/diagram.png") == len(frame.png)
    assert repr(frame) == "Frame(200×140 px, t = 3.5 s)", repr(frame)
    assert isinstance(sim.simultaneity("a"), dict)
    assert sim.scene.pucks == ["a", "b"] and sim.history is None and sim.warnings() == []
    assert repr(sim).startswith('Simulation("Engine", t = 3.5 s, 2 pucks'), repr(sim)
    assert raises(TypeError, lightcone.Simulation, "not a scene")
    del sim
    world.start(s)
    print("engine: all asserts hold")
`;

if ((await openReady("engine.py", ENGINE)) !== null) {
  await lesson.send(call("setup", "[]", NONE));
  const start = await request("start", "engine");
  if (start) {
    const scene = JSON.parse(start.args[0].$scene);
    check(scene.pucks.length === 2, `engine: started ${JSON.stringify(scene).slice(0, 200)}`);
    await lesson.send(`{"ok":null,"snapshot":${SNAPSHOT}}`);
    const d = await done("engine");
    check(d && d.error === null, `engine: ${d && d.error}`);
    check(d && JSON.stringify(d.printed) === '["engine: all asserts hold"]', `engine printed ${JSON.stringify(d && d.printed)}`);
  }
}

// ---- A lesson without setup, one that does not compile, one that hangs.

if ((await openReady("lessons/no_setup.py", "x = 1\nprint('loaded')\n")) !== null) {
  await lesson.send(call("setup", "[]", NONE));
  const d = await done("no setup");
  if (d) {
    const want = "AttributeError: lessons/no_setup.py: a lesson needs a function setup(world) that calls world.start(scene)";
    check(d.error === want, `no setup: ${JSON.stringify(d.error)}`);
    check(JSON.stringify(d.printed) === '["loaded"]', `no setup printed ${JSON.stringify(d.printed)}`);
    check(d.hooks.length === 0, `no setup's hooks ${JSON.stringify(d.hooks)}`);
  }
}

if ((await openReady("broken.py", "def setup(world):\n    return (\n")) !== null) {
  await lesson.send(call("setup", "[]", NONE));
  const d = await done("syntax error");
  check(d && /^ {2}File "broken\.py", line 2\n[\s\S]*SyntaxError: /.test(d.error), `syntax error: ${JSON.stringify(d && d.error)}`);
}

// A hook past its limit (1 s here): TimeoutError at the lesson's line, as
// on the desktop, even where the lesson catches every exception (the next
// is raised on its handler's line); the worker lives on for the next call.
for (const [name, source, line] of [
  ["hang.py", "def setup(world):\n    while True:\n        pass\n", 3],
  [
    "swallow.py",
    "def setup(world):\n    while True:\n        try:\n            while True:\n                pass\n        except BaseException:\n            pass\n",
    0,
  ],
  ["calls.py", "def tick():\n    return 1\n\n\ndef setup(world):\n    n = 0\n    while True:\n        n += tick()\n", 0],
]) {
  if ((await openReady(name, source, 1)) === null) continue;
  const t0 = await page.evaluate(() => window.__now());
  await lesson.send(call("setup", "[]", NONE));
  const d = await done(`${name} past its limit`, true);
  const ms = (await page.evaluate(() => window.__now())) - t0;
  const at = `File "${name}", line ${line || ""}`;
  check(
    d && d.error.includes(at) && d.error.endsWith("TimeoutError: the hook setup ran longer than its limit of 1 s"),
    `${name}: ${JSON.stringify(d && d.error)}`,
  );
  check(ms > 900 && ms < 3000, `${name}: stopped after ${ms} ms`);
  console.log(JSON.stringify({ lesson: name, stopped_after_ms: Math.round(ms) }));
  await lesson.send(call("on_frame", "[0.0]"));
  const after = await done(`${name}: a call after the timeout`);
  check(after && after.error === null, `${name}: the call after ${JSON.stringify(after)}`);
  await lesson.stop();
}

if ((await openReady("hang.py", "def setup(world):\n    while True:\n        pass\n")) !== null) {
  await lesson.send(call("setup", "[]", NONE));
  check((await next(500)) === null, "a hanging setup sent something");
  await lesson.stop();
  check((await lesson.state()) === "none", "state after stop");
  check((await lesson.send(call("on_frame", "[0.0]"))) === false, "send after stop");
}

// ---- A browser without JSPI: "failed", saying why, and nothing fetched.

{
  const before = fetched.length;
  const other = await browser.newPage();
  await other.goto(`${origin}/nojspi/__lesson_test.html`);
  await other.evaluate(() => window.lightconeLesson.open("a.py", "def setup(world): pass\n", 10));
  const m = await other.waitForFunction(() => window.lightconeLesson.take()[0], null, { timeout: 20_000 }).then((h) => h.jsonValue());
  check(
    m.kind === "failed" &&
      m.error.includes("lacks WebAssembly JavaScript Promise Integration (JSPI)") &&
      m.error.includes("not cross-origin isolated"),
    `without JSPI: ${JSON.stringify(m)}`,
  );
  check((await other.evaluate(() => window.lightconeLesson.state())) === "ended", "state after failed");
  const pyodide = fetched.slice(before).filter((f) => f.includes("/pyodide/"));
  check(pyodide.length === 0, `without JSPI, Pyodide was fetched: ${JSON.stringify(pyodide)}`);
  await other.close();
}

// ---- A browser without JSPI whose page is cross-origin isolated: the
// lesson's requests wait on shared memory (lesson_host.js), an answer of
// 2.6 MB in three chunks, one split inside a UTF-8 character.

const SHARED = `import lightcone


def setup(world):
    scene = lightcone.Scene(title="Two pucks")
    scene.add_puck("a", (0.5, 0.71), beta=(0.6, 0.0))
    scene.add_puck("b", (2.0, 0.71))
    world.start(scene)
    pad = world._snapshot.get("padding", "")
    print(len(pad), pad[:3], pad[-3:])
    world.say("Shared memory.")
    print("u(a) =", world.velocity("a"))
`;
async function sharedMemoryLesson(url, what) {
  const main = page;
  page = await browser.newPage();
  page.on("pageerror", (e) => fail(`${what}: uncaught in the page: ${e.message}`));
  try {
    await page.goto(url);
    // coi.js may reload the page once: wait until it is isolated and its
    // scripts have run (a new document is isolated from its first moment,
    // before lesson_host.js has loaded).
    let isolated = false;
    for (let i = 0; i < 100 && !isolated; i++) {
      isolated = await page
        .evaluate(() => self.crossOriginIsolated === true && document.readyState === "complete" && !!window.lightconeLesson)
        .catch(() => false);
      if (!isolated) await new Promise((r) => setTimeout(r, 100));
    }
    if (!check(isolated, `${what}: the page is not cross-origin isolated`)) return;
    await prepare(page);
    if ((await openReady(`${what}.py`, SHARED)) === null) return;
    await lesson.send(call("setup", "[]", NONE));
    if (!(await request("start", `${what}: setup`))) return;
    const padding = "x" + "\u00e9".repeat(1_300_000);
    await lesson.send(`{"ok":null,"snapshot":${SNAPSHOT.replace("{", `{"padding":"${padding}",`)}}`);
    if (!(await request("say", `${what}: setup`))) return;
    await lesson.send(`{"ok":null,"snapshot":${SNAPSHOT}}`);
    if (!(await request("velocity", `${what}: setup`))) return;
    await lesson.send(`{"ok":[0.75,0.0],"snapshot":${SNAPSHOT}}`);
    const d = await done(`${what}: setup`);
    check(
      d && d.error === null && JSON.stringify(d.printed) === JSON.stringify(["1300001 x\u00e9\u00e9 \u00e9\u00e9\u00e9", "u(a) = (0.75, 0.0)"]),
      `${what}: ${JSON.stringify(d)}`,
    );
    await lesson.stop();
  } finally {
    await page.close();
    page = main;
  }
}
await sharedMemoryLesson(`${origin}/nojspi-coi/__lesson_test.html`, "isolated_by_the_server");
await sharedMemoryLesson(`${origin}/nojspi-sw/__coi_test.html`, "isolated_by_coi_sw");

// ---- A request's round trip, answered from the worker's message event
// (no polling): the worker driven directly, as lesson_host.js does.

const roundTrip = await page.evaluate(
  ([source, setup, reply, n]) =>
    new Promise((resolve) => {
      const w = new Worker("./lesson_worker.js", { type: "module" });
      let t0 = 0;
      let answered = 0;
      w.onmessage = (e) => {
        if (e.data.kind === "ready") {
          t0 = performance.now();
          w.postMessage({ kind: "line", line: setup });
        } else if (e.data.kind === "line" && JSON.parse(e.data.line).done) {
          w.terminate();
          resolve({ answered, ms: (performance.now() - t0) / n, done: JSON.parse(e.data.line).done });
        } else if (e.data.kind === "line") {
          answered += 1;
          w.postMessage({ kind: "line", line: reply });
        } else {
          resolve({ error: e.data });
        }
      };
      w.postMessage({ kind: "open", name: "bench.py", source, limit: 10 });
    }),
  [
    `def setup(world):\n    for i in range(${REQUESTS}):\n        world.say(str(i))\n`,
    call("setup", "[]", NONE),
    `{"ok":null,"snapshot":${SNAPSHOT}}`,
    REQUESTS,
  ],
);
if (check(roundTrip.answered === REQUESTS && roundTrip.done && roundTrip.done.error === null, `round trips: ${JSON.stringify(roundTrip)}`)) {
  console.log(JSON.stringify({ lesson_request_round_trip_ms: +roundTrip.ms.toFixed(3) }));
}

const pyodideFiles = [...new Set(fetched.filter((f) => f.startsWith("/pyodide/")))].sort();
console.log(JSON.stringify({ lesson_worker_fetched: pyodideFiles }));
check(!fetched.some((f) => f.endsWith("(404)")), `files not found: ${JSON.stringify(fetched.filter((f) => f.endsWith("(404)")))}`);
const errors = consoleLines.filter((l) => l.startsWith("error"));
check(errors.length === 0, `console errors: ${JSON.stringify(errors)}`);

await browser.close();
server.close();
if (failed) {
  console.error(`console: ${JSON.stringify(consoleLines.slice(-30).map((l) => l.slice(0, 200)), null, 1)}`);
  console.log(`lesson worker: ${passed} passed, ${failed} failed`);
  process.exit(1);
}
console.log(`lesson worker: ${passed} passed, ${failed} failed`);
