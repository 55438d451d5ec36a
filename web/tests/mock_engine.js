// A stand-in for lightcone_engine_web.js (the engine compiled for the
// lesson's worker) while that module is not built: the same exports
// (`default` init, `lightcone_call(request) -> reply`, JSON text) over a
// tiny fake state, serving only what web/tests/lesson_worker.mjs uses.
// The test serves it at ./lightcone_engine_web.js only when web/dist has
// no real one, and says so.

export default async function init() {}

const EFFECTS = ["contraction", "light_delay", "aberration", "doppler", "searchlight", "time_dilation"];
const sims = new Map();
let nextId = 1;

function scene(state) {
  return JSON.parse(state);
}

const SCENE = {
  new: (_, [size, c, title, friction, gravity, description]) => ({
    title,
    description,
    c: c ?? size[0] / 2,
    table: { size, friction, gravity },
    pucks: [],
    observers: [],
    effects: Object.fromEntries(EFFECTS.map((e) => [e, true])),
  }),
  from_toml: (_, [text, name]) => {
    const title = /title\s*=\s*"([^"]*)"/.exec(text);
    if (!title) throw ["SceneError", `${name}: no title (the mock reads nothing else)`];
    return { ...SCENE.new(null, [[2.84, 1.42], null, title[1], 0, 9.80665, ""]) };
  },
  _from_json: (_, [text]) => scene(text),
  add_puck: (s, [name, position, beta]) => {
    if (beta && Math.hypot(beta[0], beta[1]) >= 1) throw ["SpeedOfLightError", `puck "${name}": |beta| ≥ 1`];
    s.pucks.push({ name, position, beta: beta ?? [0, 0] });
    return s;
  },
};
const GETTERS = {
  c: (s) => s.c,
  title: (s) => s.title,
  description: (s) => s.description,
  friction: (s) => s.table.friction,
  gravity: (s) => s.table.gravity,
  pucks: (s) => s.pucks.map((p) => p.name),
  observers: (s) => s.observers.map((o) => o.name),
  effects: (s) => s.effects,
  repr: (s) => `Scene(${JSON.stringify(s.title)}, ${s.pucks.length} pucks, c = ${s.c} m/s)`,
};

function serve(r) {
  if (r.class === "Scene") {
    if (r.op in GETTERS) return { ok: GETTERS[r.op](scene(r.state)), state: r.state };
    if (r.op in SCENE) {
      const s = SCENE[r.op](r.state === null ? null : scene(r.state), r.args);
      return { ok: null, state: JSON.stringify(s) };
    }
  } else if (r.class === "Simulation") {
    if (r.op === "new") {
      const id = nextId++;
      sims.set(id, { scene: scene(r.args[0]), t: 0 });
      return { ok: id };
    }
    const sim = sims.get(r.id);
    if (!sim) throw ["RuntimeError", `no simulation ${r.id}`];
    if (r.op === "drop") return { ok: sims.delete(r.id) && null };
    if (r.op === "time") return { ok: sim.t };
    if (r.op === "run_until") return { ok: (sim.t = Math.max(sim.t, r.args[0])) && null };
    if (r.op === "velocity") {
      const p = sim.scene.pucks.find((q) => q.name === r.args[0]);
      if (!p) throw ["KeyError", `no puck named ${JSON.stringify(r.args[0])}`];
      return { ok: p.beta.map((b) => b / Math.sqrt(1 - p.beta[0] ** 2 - p.beta[1] ** 2)) };
    }
  }
  throw ["RuntimeError", `the mock engine does not serve ${r.class}.${r.op}`];
}

export function lightcone_call(request) {
  try {
    return JSON.stringify(serve(JSON.parse(request)));
  } catch (e) {
    return JSON.stringify({ error: Array.isArray(e) ? e : ["RuntimeError", String(e)] });
  }
}
