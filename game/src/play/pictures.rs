//! The pictures drawn into the window's surface: each desktop view or
//! CAVE wall in its rectangle, by the one scene renderer, from what the
//! frame schedule wrote this frame.

use lightcone_render::frame::{self, FrameVertex};
use lightcone_render::gpu::Gpu;
use lightcone_render::headless::BACKGROUND;
use lightcone_render::pipeline::{Draw, Renderer};
use lightcone_tracker::cave::CaveConfig;

use super::layout::{Plan, clamp_rect};
use crate::cave::{self, Side};
use crate::model::GameState;

/// A CAVE and the stereo eyes drawn this frame (each side, its view, and
/// where it is in tracker space): what its walls are drawn from.
pub type Walls<'a> = (
    &'a CaveConfig,
    &'a [(Side, lightcone_engine::ecs::Entity, glam::DVec3)],
);

/// The scene renderer of the main window, and its vertex buffer.
pub struct Pictures {
    renderer: Renderer,
    vertices: Vec<FrameVertex>,
}

impl Pictures {
    /// A renderer for a surface of `format` and `size` (physical px),
    /// drawing `samples` samples a pixel (a window's
    /// [`Gpu::window_samples`], a picture for a file's
    /// [`lightcone_render::pipeline::SAMPLES`]).
    pub fn new(gpu: &Gpu, format: wgpu::TextureFormat, size: (u32, u32), samples: u32) -> Self {
        Self {
            renderer: Renderer::new(&gpu.device, format, size.0, size.1, samples),
            vertices: Vec::new(),
        }
    }

    /// Draws every rectangle of `plans` into `target` (of `size`), the
    /// first clearing it to the background. One renderer draws every
    /// view, each submitted before the next is written: its multisampled
    /// target (or, with one sample a pixel, `target` itself) then holds
    /// the views drawn so far, which the next one loads (and resolves
    /// whole).
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        target: &wgpu::TextureView,
        size: (u32, u32),
        plans: &[([f32; 4], Plan)],
        state: &GameState,
        cave: Option<Walls<'_>>,
    ) {
        let (w, h) = (size.0 as f32, size.1 as f32);
        let mut cleared = false;
        for &(rect, plan) in plans {
            let Some(view_proj) = self.build(plan, rect, state, cave) else {
                continue;
            };
            let Some(rect) = clamp_rect(rect, w, h) else {
                continue;
            };
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("scene view"),
                });
            self.renderer.resize(&gpu.device, size.0, size.1);
            self.renderer.render(
                &gpu.device,
                &gpu.queue,
                &mut encoder,
                target,
                Draw {
                    vertices: &self.vertices,
                    view_proj,
                    clear: (!cleared).then_some(BACKGROUND),
                    viewport: Some(rect),
                },
            );
            gpu.queue.submit([encoder.finish()]);
            cleared = true;
        }
    }

    /// Builds the vertices of one rectangle's picture; returns its
    /// matrix, or `None` when there is nothing to draw (its view did not
    /// run, the eye is behind a wall).
    fn build(
        &mut self,
        plan: Plan,
        rect: [f32; 4],
        state: &GameState,
        cave: Option<Walls<'_>>,
    ) -> Option<glam::Mat4> {
        self.vertices.clear();
        match (plan, cave) {
            (Plan::Wall(i), Some((c, stereo))) => {
                let &(_, view, tracker_eye) = stereo.first()?;
                cave::wall_frame(state, c, &c.walls[i], view, tracker_eye, &mut self.vertices)
            }
            (Plan::Desktop(pane), _) => {
                let view = state.view_of(pane)?;
                let (apparent, camera) = (state.apparent(view)?, state.camera(view)?);
                frame::build_view(apparent, &state.meshes, &mut self.vertices);
                Some(camera.view_proj(rect[2] / rect[3]))
            }
            (Plan::Wall(_), None) => None,
        }
    }
}
