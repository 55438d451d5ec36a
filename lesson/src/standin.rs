//! The `lightcone` module's `Scene` and `Simulation` for a lesson that has
//! no pyo3 extension: the browser's worker, where Pyodide runs the lesson
//! and this crate, compiled to wasm (`web-engine/`), answers the Python
//! stand-ins (`web/python/_lightcone.py`) with the same operations as the
//! extension's classes (`scene_code`, `query`).
//!
//! One JSON request a call:
//! `{"class": "Scene", "op": OP, "state": SCENE_JSON | null, "args": [...],
//! "kwargs": {...}}` answered `{"ok": value, "state": SCENE_JSON}`, or
//! `{"class": "Simulation", "op": OP, "id": ID, "args": [...], "kwargs":
//! {...}}` answered `{"ok": value}`; a refusal is `{"error": [kind,
//! message]}`, `kind` the Python exception's name. Values are encoded as
//! the lesson protocol's (`crate::protocol`). A Scene's state is its JSON
//! (`Scene._to_json`), rebuilt through every check when it comes back.

use std::collections::BTreeMap;

use lightcone_engine::scene::{self, Effect, Scene};
use serde::Deserialize;
use serde_json::{Map, Value, json};

use crate::args::{Arg, Bound, Vector};
use crate::error::{ErrorKind, WorldError, WorldResult};
use crate::protocol::{frame, pixels, record, scene_from_json};
use crate::simulation::SimulationCore;
use crate::{query, scene_code};

/// Most simulations a lesson may hold at once (each a whole board): past
/// it `Simulation(...)` raises, so a lesson cannot fill the worker's
/// memory with them.
pub const MAX_SIMULATIONS: usize = 64;

/// The simulations a lesson holds, by id.
#[derive(Default)]
pub struct Objects {
    simulations: BTreeMap<u64, SimulationCore>,
    next: u64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Request {
    class: String,
    op: String,
    #[serde(default)]
    state: Option<String>,
    #[serde(default)]
    id: Option<u64>,
    #[serde(default)]
    args: Vec<Value>,
    #[serde(default)]
    kwargs: Map<String, Value>,
}

impl Objects {
    /// Answers one request (see the module's docs), as JSON text.
    pub fn call(&mut self, request: &str) -> String {
        let reply = serde_json::from_str::<Request>(request)
            .map_err(|e| WorldError::value(format!("a request the engine cannot read: {e}")))
            .and_then(|r| self.answer(&r));
        match reply {
            Ok(v) => v.to_string(),
            Err(e) => json!({ "error": [e.kind.name(), e.message] }).to_string(),
        }
    }

    fn answer(&mut self, r: &Request) -> WorldResult<Value> {
        match r.class.as_str() {
            "Scene" => {
                let mut scene = r.state.as_deref().map(scene_from_json).transpose()?;
                let ok = scene_op(&mut scene, &r.op, &r.args, &r.kwargs)?;
                let state = match &scene {
                    Some(s) => Value::String(to_json(s)?),
                    None => Value::Null,
                };
                Ok(json!({ "ok": ok, "state": state }))
            }
            "Simulation" => Ok(json!({ "ok": self.simulation_op(r)? })),
            other => Err(WorldError::value(format!("no class {other:?} here"))),
        }
    }

    fn simulation_op(&mut self, r: &Request) -> WorldResult<Value> {
        let (op, args, kwargs) = (r.op.as_str(), r.args.as_slice(), &r.kwargs);
        let b =
            |params: &'static [&'static str]| Bound::new("Simulation", op, params, args, kwargs);
        if op == "new" {
            let a = b(&["scene", "history"])?;
            let text = a.req::<String>(0)?;
            let scene = scene_from_json(&text)?;
            if self.simulations.len() >= MAX_SIMULATIONS {
                return Err(WorldError::new(
                    ErrorKind::Runtime,
                    format!("a lesson may hold at most {MAX_SIMULATIONS} simulations at once"),
                ));
            }
            let simulation = SimulationCore::new(&scene, a.opt(1)?)?;
            self.next += 1;
            self.simulations.insert(self.next, simulation);
            return Ok(json!(self.next));
        }
        let id =
            r.id.ok_or_else(|| WorldError::value("a Simulation request needs its id"))?;
        if op == "drop" {
            self.simulations.remove(&id);
            return Ok(Value::Null);
        }
        let s = self
            .simulations
            .get_mut(&id)
            .ok_or_else(|| WorldError::new(ErrorKind::Runtime, "this simulation was dropped"))?;
        let now = s.time();
        Ok(match op {
            "run_until" => {
                let a = b(&["t"])?;
                let t = query::finite_time(a.req(0)?)?;
                s.advance_to(t);
                s.forget_old_records();
                Value::Null
            }
            "step" => {
                let a = b(&["dt"])?;
                let t = query::finite_time(now + a.req::<f64>(0)?)?;
                s.advance_to(t);
                s.forget_old_records();
                Value::Null
            }
            "impulse" => {
                let a = b(&["name", "du"])?;
                let [x, y] = a.req::<Vector<2>>(1)?.0;
                query::impulse(s.billiard_mut(), &a.req::<String>(0)?, now, (x, y))?;
                Value::Null
            }
            "collisions" => {
                b(&[])?;
                let b = s.billiard();
                let all: WorldResult<Vec<Value>> = b
                    .collisions()
                    .iter()
                    .map(|c| {
                        record(
                            "Collision",
                            &lightcone_engine::report::CollisionLine::new(b, c),
                        )
                    })
                    .collect();
                Value::Array(all?)
            }
            "state" => {
                b(&[])?;
                record(
                    "State",
                    &lightcone_engine::report::StateLine::new(s.billiard(), now),
                )?
            }
            "observe" => {
                let a = b(&["observer", "vertices", "effects", "at"])?;
                let t = query::past_time(a.opt(3)?, now)?;
                let fx = query::effects_from(s.scene().effects, a.opt(2)?)?;
                let observer = a.opt::<String>(0)?;
                let report = s.observe(observer.as_deref(), t, a.opt(1)?.unwrap_or(false), fx)?;
                record("Observation", &report)?
            }
            "velocity" => {
                let a = b(&["name"])?;
                let (x, y) = query::velocity(s.billiard(), &a.req::<String>(0)?, now)?;
                json!([x, y])
            }
            "simultaneity" => {
                let a = b(&["frame", "at"])?;
                let t = query::past_time(a.opt(1)?, now)?;
                let line = query::simultaneity(s.scene(), s.billiard(), &a.req::<String>(0)?, t)?;
                serde_json::to_value(line).map_err(|e| WorldError::value(e.to_string()))?
            }
            "diagram" => {
                let a = b(&["path", "observer", "size", "at", "axis", "frame"])?;
                let t = query::past_time(a.opt(3)?, now)?;
                let observer = a.opt::<String>(1)?;
                let axis = a.opt::<String>(4)?.unwrap_or_else(|| "x".to_owned());
                let puck = a.opt::<String>(5)?;
                let image = query::diagram(
                    s.scene(),
                    s.billiard(),
                    t,
                    observer.as_deref(),
                    pixels(&a, 2, (1000, 700))?,
                    &axis,
                    puck.as_deref(),
                )?;
                let path = a.opt::<String>(0)?.map(std::path::PathBuf::from);
                frame(&image, t, path.as_deref())?
            }
            "time" => {
                b(&[])?;
                json!(now)
            }
            "history" => {
                b(&[])?;
                json!(s.billiard().history())
            }
            "forgotten_before" => {
                b(&[])?;
                json!(s.billiard().forgotten_before())
            }
            "scene" => {
                b(&[])?;
                Value::String(to_json(s.scene())?)
            }
            "warnings" => {
                b(&[])?;
                json!(s.billiard().warnings())
            }
            "repr" => {
                b(&[])?;
                Value::String(format!(
                    "Simulation({:?}, t = {} s, {} pucks, {} collisions)",
                    s.scene().title,
                    now,
                    s.billiard().len(),
                    s.billiard().collisions().len()
                ))
            }
            "positions" | "velocities" | "render" => {
                return Err(WorldError::new(
                    ErrorKind::Runtime,
                    format!(
                        "Simulation.{op} is not available in a lesson in the browser (the desktop's `lightcone` module has it)"
                    ),
                ));
            }
            _ => return Err(WorldError::value(format!("Simulation has no {op:?}"))),
        })
    }
}

fn to_json(scene: &Scene) -> WorldResult<String> {
    serde_json::to_string(scene).map_err(|e| WorldError::value(e.to_string()))
}

/// Runs Scene operation `op` on `scene` (`None` before a constructor).
fn scene_op(
    scene: &mut Option<Scene>,
    op: &str,
    args: &[Value],
    kwargs: &Map<String, Value>,
) -> WorldResult<Value> {
    let b = |params: &'static [&'static str]| Bound::new("Scene", op, params, args, kwargs);
    // The constructors: a new state.
    let made = match op {
        "new" => {
            let a = b(&["size", "c", "title", "friction", "gravity", "description"])?;
            let size = a
                .opt::<Vector<2>>(0)?
                .map_or((2.84, 1.42), |v| (v.0[0], v.0[1]));
            Some(scene_code::new(
                size,
                a.opt(1)?,
                &a.opt::<String>(2)?.unwrap_or_else(|| "scene".to_owned()),
                a.opt(3)?.unwrap_or(0.0),
                a.opt(4)?.unwrap_or(9.80665),
                &a.opt::<String>(5)?.unwrap_or_default(),
            )?)
        }
        "from_toml" => {
            let a = b(&["text", "name"])?;
            let name = a.opt::<String>(1)?.unwrap_or_else(|| "<string>".to_owned());
            Some(scene::parse(&a.req::<String>(0)?, &name)?)
        }
        "load" => {
            let a = b(&["path"])?;
            Some(scene::load(std::path::Path::new(&a.req::<String>(0)?))?)
        }
        "_from_json" => {
            let a = b(&["text"])?;
            Some(scene_from_json(&a.req::<String>(0)?)?)
        }
        _ => None,
    };
    if let Some(made) = made {
        *scene = Some(made);
        return Ok(Value::Null);
    }
    let s = scene
        .as_mut()
        .ok_or_else(|| WorldError::value(format!("Scene.{op}: no scene")))?;
    if let Some(name) = op.strip_prefix('=') {
        let [value] = args else {
            return Err(crate::args::type_error(format!(
                "Scene.{name} = takes one value"
            )));
        };
        let arg = Arg { name, value };
        match name {
            "friction" => {
                let g = s.table.gravity;
                s.set_friction(arg.get()?, g)?;
            }
            "gravity" => {
                let f = s.table.friction;
                s.set_friction(f, arg.get()?)?;
            }
            "c" => scene_code::set_c(s, arg.get()?)?,
            _ => return Err(WorldError::value(format!("Scene.{name} cannot be set"))),
        }
        return Ok(Value::Null);
    }
    let pair = |v: Option<Vector<2>>| v.map(|v| (v.0[0], v.0[1]));
    Ok(match op {
        "add_puck" => {
            let a = b(&[
                "name", "position", "beta", "u", "radius", "height", "mass", "color", "velocity",
            ])?;
            let name = a.req::<String>(0)?;
            let color = a.opt::<String>(7)?;
            let [x, y] = a.req::<Vector<2>>(1)?.0;
            let puck = scene_code::PuckArgs {
                name: &name,
                position: (x, y),
                beta: pair(a.opt(2)?),
                u: pair(a.opt(3)?),
                radius: a.opt(4)?.unwrap_or(0.0305),
                height: a.opt(5)?.unwrap_or(0.02),
                mass: a.opt(6)?.unwrap_or(0.21),
                color: color.as_deref(),
                velocity: pair(a.opt(8)?),
            };
            scene_code::add_puck(s, &puck)?;
            Value::Null
        }
        "add_observer" => {
            let a = b(&["name", "position", "look_at", "beta"])?;
            let look_at = a.opt::<Vector<3>>(2)?.map(|v| v.0);
            let beta = a.opt::<Vector<3>>(3)?.map(|v| v.0);
            let name = a.req::<String>(0)?;
            scene_code::add_observer(s, &name, a.req::<Vector<3>>(1)?.0, look_at, beta)?;
            Value::Null
        }
        "set_effect" => {
            let a = b(&["name", "on"])?;
            s.effects
                .set(query::effect(&a.req::<String>(0)?)?, a.req(1)?);
            Value::Null
        }
        "friction" => json!(s.table.friction),
        "gravity" => json!(s.table.gravity),
        "c" => json!(s.c),
        "title" => json!(s.title),
        "description" => json!(s.description),
        "pucks" => json!(scene_code::pucks(s)),
        "observers" => json!(scene_code::observers(s)),
        "effects" => Value::Object(
            Effect::ALL
                .iter()
                .map(|e| (e.key().to_owned(), Value::Bool(s.effects.is_on(*e))))
                .collect(),
        ),
        "repr" => json!(scene_code::describe(s)),
        _ => return Err(WorldError::value(format!("Scene has no {op:?}"))),
    })
}
