//! One frame's geometry: every triangle of every puck and of the table, at
//! the apparent positions the optics computed, in the observer's frame and
//! relative to the eye (so f32 is enough), with Doppler factor and
//! intensity per vertex.
//!
//! [`build_view`] draws a view of the frame schedule (its `Apparent`, the
//! one optics output): the window, the CAVE walls, `lightcone render`,
//! `record`, Python's `render` and the tests all go through it.

use bytemuck::{Pod, Zeroable};
use glam::{DVec3, Mat4, Vec3};
use lightcone_engine::ecs::{Apparent, BodyRef, Entity, Simulation};
use lightcone_engine::optics::Eye;
use lightcone_engine::scene::{Color, Effects, Scene};
use lightcone_engine::worldline::RestShape;

/// One vertex as the GPU takes it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct FrameVertex {
    /// Apparent position, observer's frame, relative to the eye, m.
    pub position: [f32; 3],
    /// Base colour, linear RGB.
    pub colour: [f32; 3],
    /// Doppler factor (1: no shift).
    pub doppler: f32,
    /// Brightness factor (1: unchanged).
    pub intensity: f32,
}

/// Which view to draw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewKind {
    /// What the observer sees, with the scene's effects.
    Seen,
    /// The board-frame "truth": every body where it is at this board time,
    /// contracted, no light delay, no aberration, no colour change; each
    /// clock reads the body's proper time at this board time (the time
    /// dilation effect, which without light delay is `τ(t)`), so the truth
    /// pane and the panel's proper times agree.
    Truth,
}

impl ViewKind {
    /// The effects this view uses, given the scene's.
    #[must_use]
    pub fn effects(self, scene: Effects) -> Effects {
        match self {
            ViewKind::Seen => scene,
            ViewKind::Truth => Effects {
                contraction: true,
                time_dilation: true,
                ..Effects::NONE
            },
        }
    }
}

/// A pinhole camera at the eye.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Viewing direction (observer's frame).
    pub forward: DVec3,
    /// Vertical field of view, radians.
    pub fovy: f64,
}

impl From<lightcone_engine::camera::Camera> for Camera {
    fn from(c: lightcone_engine::camera::Camera) -> Self {
        Self {
            forward: c.forward,
            fovy: c.fovy,
        }
    }
}

impl Camera {
    /// View-projection matrix for an image of aspect `width / height`:
    /// right-handed, z up, depth in [0, 1] as wgpu wants.
    #[must_use]
    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        let f = self.forward.normalize_or(DVec3::Y).as_vec3();
        let up = if f.cross(Vec3::Z).length() < 1e-6 {
            Vec3::Y
        } else {
            Vec3::Z
        };
        let view = glam::camera::rh::view::look_to_mat4(Vec3::ZERO, f, up);
        // wgpu's clip space is DirectX's: y up, depth in [0, 1].
        let proj =
            glam::camera::rh::proj::directx::perspective(self.fovy as f32, aspect, 0.01, 200.0);
        proj * view
    }
}

fn linear(c: Color) -> [f32; 3] {
    let f = |x: u8| (f32::from(x) / 255.0).powf(2.2);
    [f(c.r), f(c.g), f(c.b)]
}

/// Height of the cushions above the board, m.
pub const CUSHION_HEIGHT: f64 = lightcone_engine::worldline::mesh::CUSHION_HEIGHT;
/// Width of the cushions, m.
pub const CUSHION_WIDTH: f64 = lightcone_engine::worldline::mesh::CUSHION_WIDTH;

const CLOTH: [f32; 3] = [0.02, 0.16, 0.05];
const CUSHION: [f32; 3] = [0.05, 0.09, 0.04];

/// The dark stripe on each puck's side facing its rest-frame +x: it shows
/// the puck's orientation and how its shape is distorted.
fn marked(shape: &RestShape, tri: [u32; 3]) -> bool {
    let c = tri
        .iter()
        .map(|&i| shape.vertices[i as usize])
        .sum::<DVec3>()
        / 3.0;
    let r = c.truncate().length();
    r > 0.0 && c.x / r > 0.94
}

/// The eye of observer `index` of `scene` at board time `t` (constant
/// velocity from its position at t = 0), and the way it faces: towards its
/// `look_at` (else the table's centre) with a 60° field. That is where a
/// free eye taken over from it starts looking; to draw what it sees, use
/// [`scene_view`], which frames the table as every view does.
#[must_use]
pub fn eye_of(scene: &Scene, index: usize, t: f64) -> (Eye, Camera) {
    let o = &scene.observers[index];
    let eye = Eye {
        event: lightcone_engine::spacetime::Event::new(t, o.position + o.u.velocity(scene.c) * t),
        u: o.u,
    };
    let camera = Camera {
        forward: o.target(scene.table.size) - o.position,
        fovy: std::f64::consts::FRAC_PI_3,
    };
    (eye, camera)
}

/// The triangles and colours of every body a view of a
/// [`Simulation`] lists in its [`Apparent`], built once per simulation
/// (meshes do not change).
pub struct ViewMeshes {
    pucks: Vec<BodyMesh>,
    fixtures: Vec<BodyMesh>,
}

/// One body's triangles, each with its colour.
#[derive(Default)]
struct BodyMesh {
    triangles: Vec<[u32; 3]>,
    colours: Vec<[f32; 3]>,
}

impl ViewMeshes {
    /// The meshes of every puck and fixture of `sim`: pucks in their scene
    /// colour with the dark stripe, the cloth and the cushions in theirs
    /// (the framing marks have no triangles).
    pub fn new(sim: &mut Simulation) -> Self {
        let mut pucks = Vec::new();
        let mut fixtures = Vec::new();
        for (body, mesh, tint) in sim.body_meshes() {
            let shape = &mesh.shape;
            let colours = match tint {
                Some(t) => {
                    let base = linear(t);
                    let dark = [base[0] * 0.15, base[1] * 0.15, base[2] * 0.15];
                    shape
                        .triangles
                        .iter()
                        .map(|&t| if marked(shape, t) { dark } else { base })
                        .collect()
                }
                None => {
                    let colour = if shape.vertices.iter().all(|v| v.z <= 1e-9) {
                        CLOTH
                    } else {
                        CUSHION
                    };
                    vec![colour; shape.triangles.len()]
                }
            };
            let (list, i) = match body {
                BodyRef::Puck(i) => (&mut pucks, i),
                BodyRef::Fixture(i) => (&mut fixtures, i),
            };
            if list.len() <= i {
                list.resize_with(i + 1, BodyMesh::default);
            }
            list[i] = BodyMesh {
                triangles: shape.triangles.clone(),
                colours,
            };
        }
        Self { pucks, fixtures }
    }

    fn of(&self, body: BodyRef) -> Option<&BodyMesh> {
        match body {
            BodyRef::Puck(i) => self.pucks.get(i),
            BodyRef::Fixture(i) => self.fixtures.get(i),
        }
    }
}

/// One triangle corner of a view, in f64: apparent position (observer's
/// frame with aberration, relative to the eye), Doppler factor, intensity,
/// base colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ApparentCorner {
    /// Apparent position, m.
    pub position: DVec3,
    /// Doppler factor (1: no shift).
    pub doppler: f64,
    /// Brightness factor (1: unchanged).
    pub intensity: f64,
    /// Base colour, linear RGB.
    pub colour: [f32; 3],
}

/// Every triangle corner of what a view saw (its [`Apparent`], the frame
/// schedule's output): the frame path of the window and of headless
/// rendering, before the copy to f32.
#[must_use]
pub fn view_corners(apparent: &Apparent, meshes: &ViewMeshes) -> Vec<ApparentCorner> {
    let mut out = Vec::new();
    for body in &apparent.bodies {
        let Some(mesh) = meshes.of(body.body) else {
            continue;
        };
        for (tri, &colour) in mesh.triangles.iter().zip(&mesh.colours) {
            for &i in tri {
                let i = i as usize;
                let (Some(s), Some(&intensity)) = (body.seen.get(i), body.intensity.get(i)) else {
                    continue;
                };
                out.push(ApparentCorner {
                    position: s.position,
                    doppler: s.doppler,
                    intensity,
                    colour,
                });
            }
        }
    }
    out
}

/// The triangle list of what a view saw, as the GPU takes it.
pub fn build_view(apparent: &Apparent, meshes: &ViewMeshes, out: &mut Vec<FrameVertex>) {
    out.clear();
    out.extend(
        view_corners(apparent, meshes)
            .into_iter()
            .map(|c| FrameVertex {
                position: c.position.as_vec3().to_array(),
                colour: c.colour,
                doppler: c.doppler as f32,
                intensity: c.intensity as f32,
            }),
    );
}

/// A simulation of `scene` at board time `t` with one view of observer
/// `index`: the scene's effects for [`ViewKind::Seen`], the truth's for
/// [`ViewKind::Truth`], its camera aimed as the observer's
/// [`lightcone_engine::scene::ObserverSpec::framing`] says for an image of
/// `aspect` = width / height (fitted to the whole table, as this eye sees
/// it, unless the scene names a `look_at`).
#[must_use]
pub fn scene_view(
    scene: &Scene,
    index: usize,
    t: f64,
    kind: ViewKind,
    aspect: f64,
) -> (Simulation, Entity) {
    let mut sim = Simulation::new(scene);
    let o = &scene.observers[index];
    let view = sim.views()[index];
    let effects = kind.effects(scene.effects);
    sim.set_view_effects(view, effects);
    sim.set_framing(view, o.framing(aspect));
    // Run here to `t`: only what the view can still see is kept.
    sim.run_far_to(view, t);
    (sim, view)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scene's table corners (cushions included) as `eye` sees them.
    fn corners_seen(scene: &Scene, eye: &Eye, aberration: bool) -> Vec<DVec3> {
        crate::camera::table_corners(scene.table.size, CUSHION_HEIGHT, CUSHION_WIDTH)
            .into_iter()
            .map(|p| eye.see_static(p, scene.c, aberration).position)
            .collect()
    }

    #[test]
    fn headless_views_frame_the_whole_table() {
        // Every shipped scene names no `look_at`: `render`, Python's
        // `render` and `record` (all the schedule's views, `scene_view`)
        // fit the whole table as the view's eye sees it, with the engine's
        // margin, tight on one axis.
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes");
        let tight = 1.0 / (1.0 + lightcone_engine::camera::FIT_MARGIN);
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            let scene = lightcone_engine::scene::load(&path).unwrap();
            for (index, o) in scene.observers.iter().enumerate() {
                assert!(o.look_at.is_none(), "{}: {}", path.display(), o.name);
                for aspect in [16.0 / 9.0, 1.0, 0.75] {
                    for kind in [ViewKind::Seen, ViewKind::Truth] {
                        let effects = kind.effects(scene.effects);
                        let (sim, view) = scene_view(&scene, index, 1.0, kind, aspect);
                        let camera: Camera = sim.camera(view).unwrap().into();
                        let eye = sim.apparent(view).unwrap().eye.unwrap();
                        let what = format!("{} {} {aspect} {kind:?}", path.display(), o.name);
                        let mut widest = 0.0f64;
                        for p in corners_seen(&scene, &eye, effects.aberration) {
                            let (x, y) = crate::camera::ndc(&camera, aspect, p).unwrap();
                            assert!(x.abs() <= tight + 1e-9 && y.abs() <= tight + 1e-9, "{what}");
                            widest = widest.max(x.abs()).max(y.abs());
                        }
                        assert!(widest > tight - 1e-3, "{what}: {widest}");
                    }
                }
            }
        }
    }

    #[test]
    fn a_named_look_at_keeps_its_sixty_degree_camera() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../assets/scenes/paper_carom.toml");
        let mut scene = lightcone_engine::scene::load(&path).unwrap();
        let target = DVec3::new(0.5, 0.3, 0.0);
        scene.observers[0].look_at = Some(target);
        let forward = (target - scene.observers[0].position).normalize();
        let (sim, view) = scene_view(&scene, 0, 1.0, ViewKind::Seen, 2.0);
        let c: Camera = sim.camera(view).unwrap().into();
        assert!((c.forward.normalize() - forward).length() < 1e-12);
        assert!((c.fovy - std::f64::consts::FRAC_PI_3).abs() < 1e-12);
    }

    #[test]
    fn every_vertex_is_finite_in_every_shipped_scene() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes");
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            let scene = lightcone_engine::scene::load(&path).unwrap();
            let mut all = scene.clone();
            for e in lightcone_engine::scene::Effect::ALL {
                all.effects.set(e, true);
            }
            let mut none = scene.clone();
            none.effects = Effects::NONE;
            let mut out = Vec::new();
            for s in [&scene, &all, &none] {
                let (mut sim, view) = scene_view(s, 0, 0.0, ViewKind::Seen, 16.0 / 9.0);
                let meshes = ViewMeshes::new(&mut sim);
                for t in [0.0, 1.0, 5.0] {
                    sim.advance_to(t);
                    build_view(sim.apparent(view).unwrap(), &meshes, &mut out);
                    assert!(!out.is_empty() && out.len() % 3 == 0);
                    for v in &out {
                        assert!(
                            v.position.iter().all(|x| x.is_finite()),
                            "{}",
                            path.display()
                        );
                        assert!(v.doppler.is_finite() && v.intensity.is_finite());
                    }
                }
            }
        }
    }
}
