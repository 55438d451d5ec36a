//! One borderless window per video output of the CAVE file (`[[output]]`):
//! each shows one wall, for one eye or a stereo pair side by side or top
//! and bottom, with the off-axis projection of that eye through that wall.
//! The main window keeps the panels and tiles the walls no output shows
//! (the desktop preview).
//!
//! Every output draws what the game's frame schedule wrote for its eye this
//! frame ([`crate::cave::stereo_views`]), so all walls show the same board
//! time: they are drawn and presented one after the other in the same
//! frame of the event loop.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use lightcone_render::frame::FrameVertex;
use lightcone_render::gpu::Gpu;
use lightcone_render::headless::BACKGROUND;
use lightcone_render::pipeline::{Draw, Renderer};
use lightcone_tracker::cave::{CaveConfig, Output, Placement};
use winit::event_loop::ActiveEventLoop;
use winit::window::{Fullscreen, Window, WindowId};

use crate::cave::{self, Side, eye_viewports};
use crate::model::GameState;

/// A window showing one `[[output]]`.
pub struct OutputWindow {
    /// Its entry in the CAVE file.
    pub output: Output,
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: Option<wgpu::SurfaceConfiguration>,
    renderer: Option<Renderer>,
}

/// Opens a window for every output of `cave` and a surface on it, with
/// `instance` (before the GPU is chosen, so the adapter can be checked
/// against every surface). Errors name the output and, for an unknown
/// monitor, list the monitors there are.
pub fn open(
    event_loop: &ActiveEventLoop,
    instance: &wgpu::Instance,
    cave: &CaveConfig,
) -> Result<Vec<OutputWindow>, String> {
    let monitors: Vec<_> = event_loop.available_monitors().collect();
    cave.outputs
        .iter()
        .enumerate()
        .map(|(i, o)| {
            let mut attributes = Window::default_attributes()
                .with_title(format!("Lightcone CAVE: {}", o.name))
                .with_decorations(false);
            match &o.placement {
                Placement::Region(at, size) => {
                    let on_a_monitor = monitors.iter().any(|m| {
                        let (p, s) = (m.position(), m.size());
                        i64::from(at[0]) < i64::from(p.x) + i64::from(s.width)
                            && i64::from(p.x) < i64::from(at[0]) + i64::from(size[0])
                            && i64::from(at[1]) < i64::from(p.y) + i64::from(s.height)
                            && i64::from(p.y) < i64::from(at[1]) + i64::from(size[1])
                    });
                    if !monitors.is_empty() && !on_a_monitor {
                        crate::errln!(
                            "lightcone play: {}: output[{i}] ({:?}).region \
                             [{}, {}, {}, {}] lies on no monitor: its window will not be seen",
                            cave.label(),
                            o.name,
                            at[0],
                            at[1],
                            size[0],
                            size[1]
                        );
                    }
                    attributes = attributes
                        .with_position(winit::dpi::PhysicalPosition::new(at[0], at[1]))
                        .with_inner_size(winit::dpi::PhysicalSize::new(size[0], size[1]));
                }
                Placement::Monitor(name) => {
                    let monitor = monitors
                        .iter()
                        .find(|m| m.name().as_deref() == Some(name.as_str()))
                        .ok_or_else(|| {
                            let names: Vec<String> = monitors
                                .iter()
                                .map(|m| m.name().unwrap_or_else(|| "(unnamed)".into()))
                                .collect();
                            format!(
                                "{}: output[{i}] ({:?}).monitor: no monitor is named \
                                 {name:?} (monitors: {})",
                                cave.label(),
                                o.name,
                                if names.is_empty() {
                                    "none".to_owned()
                                } else {
                                    names.join(", ")
                                }
                            )
                        })?;
                    // The monitor's place and size too: without a window
                    // manager to honour full screen, the window still covers
                    // its monitor (not winit's default 800 × 600).
                    attributes = attributes
                        .with_position(monitor.position())
                        .with_inner_size(monitor.size())
                        .with_fullscreen(Some(Fullscreen::Borderless(Some(monitor.clone()))));
                }
            }
            let window = Arc::new(
                event_loop
                    .create_window(attributes)
                    .map_err(|e| format!("CAVE output {:?}: cannot open a window: {e}", o.name))?,
            );
            let surface = instance.create_surface(window.clone()).map_err(|e| {
                format!("CAVE output {:?}: cannot draw into its window: {e}", o.name)
            })?;
            Ok(OutputWindow {
                output: o.clone(),
                window,
                surface,
                config: None,
                renderer: None,
            })
        })
        .collect()
}

impl OutputWindow {
    /// Its window's id, to route window events.
    pub fn id(&self) -> WindowId {
        self.window.id()
    }

    /// Its size now, physical px.
    fn size(&self) -> (u32, u32) {
        let s = self.window.inner_size();
        (s.width.max(1), s.height.max(1))
    }

    /// Configures the surface for `gpu` at the window's size (also after a
    /// resize).
    pub fn configure(&mut self, gpu: &Gpu) -> Result<(), String> {
        let (w, h) = self.size();
        let mut config = match self.config.take() {
            Some(c) => c,
            None => self
                .surface
                .get_default_config(&gpu.handle, w, h)
                .ok_or_else(|| {
                    format!(
                        "CAVE output {:?}: the adapter {} cannot draw into its window",
                        self.output.name, gpu.adapter
                    )
                })?,
        };
        config.usage |=
            wgpu::TextureUsages::COPY_SRC & self.surface.get_capabilities(&gpu.handle).usages;
        (config.width, config.height) = (w, h);
        self.surface.configure(&gpu.device, &config);
        match &mut self.renderer {
            Some(r) => r.resize(&gpu.device, w, h),
            None => {
                self.renderer = Some(Renderer::new(
                    &gpu.device,
                    config.format,
                    w,
                    h,
                    gpu.window_samples(),
                ))
            }
        }
        self.config = Some(config);
        Ok(())
    }

    /// Draws its wall for each of its eyes (`stereo`: each side drawn this
    /// frame, its view and tracker-space eye) and presents it; with `shot`,
    /// also saves it as `shot` with `.<name>.png` for its extension.
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        game: &GameState,
        cave: &CaveConfig,
        stereo: &[(Side, lightcone_engine::ecs::Entity, glam::DVec3)],
        shot: Option<&Path>,
    ) -> Result<(), String> {
        if self.config.as_ref().map(|c| (c.width, c.height)) != Some(self.size()) {
            self.configure(gpu)?;
        }
        let (Some(config), Some(renderer)) = (&self.config, &mut self.renderer) else {
            return Ok(());
        };
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&gpu.device, config);
                return Ok(());
            }
            _ => return Ok(()),
        };
        let target = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        let (w, h) = (config.width as f32, config.height as f32);
        let wall = &cave.walls[self.output.wall];
        let mut vertices: Vec<FrameVertex> = Vec::new();
        let mut cleared = false;
        for (side, part) in eye_viewports(self.output.eyes) {
            let Some(&(_, view, tracker_eye)) = stereo.iter().find(|s| s.0 == side) else {
                continue;
            };
            vertices.clear();
            // An eye behind the wall's plane sees nothing on it: background.
            let view_proj = cave::wall_frame(game, cave, wall, view, tracker_eye, &mut vertices);
            let rect = [part[0] * w, part[1] * h, part[2] * w, part[3] * h];
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("CAVE output"),
                });
            renderer.render(
                &gpu.device,
                &gpu.queue,
                &mut encoder,
                &target,
                Draw {
                    vertices: if view_proj.is_some() { &vertices } else { &[] },
                    view_proj: view_proj.unwrap_or(glam::Mat4::IDENTITY),
                    clear: (!cleared).then_some(BACKGROUND),
                    viewport: Some(rect),
                },
            );
            gpu.queue.submit([encoder.finish()]);
            cleared = true;
        }
        if let Some(path) = shot {
            super::screenshot::save_frame(gpu, config, &frame.texture, &self.shot_path(path))?;
        }
        gpu.queue.present(frame);
        Ok(())
    }

    /// Where its screenshot goes beside the main window's `path`:
    /// `shot.png` → `shot.<name>.png` (spaces and slashes in the name as
    /// `_`).
    pub fn shot_path(&self, path: &Path) -> PathBuf {
        shot_path(path, &self.output.name)
    }
}

/// `shot.png` → `shot.<name>.png`, with characters a file name cannot hold
/// as `_`.
pub fn shot_path(path: &Path, name: &str) -> PathBuf {
    let clean: String = name
        .chars()
        .map(|ch| {
            if ch.is_alphanumeric() || ch == '-' || ch == '_' {
                ch
            } else {
                '_'
            }
        })
        .collect();
    path.with_extension(format!("{clean}.png"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cave::sides_needed;
    use lightcone_tracker::cave::OutputEyes;

    #[test]
    fn stereo_pairs_split_the_output_and_every_eye_is_drawn_once() {
        let halves = eye_viewports(OutputEyes::SideBySide);
        assert_eq!(halves[0], (Side::Left, [0.0, 0.0, 0.5, 1.0]));
        assert_eq!(halves[1], (Side::Right, [0.5, 0.0, 0.5, 1.0]));
        let halves = eye_viewports(OutputEyes::TopBottom);
        assert_eq!(halves[0].1[3] + halves[1].1[3], 1.0);
        let text = format!(
            "{}\n[[output]]\nwall = \"front\"\neye = \"side-by-side\"\nregion = [0, 0, 8, 8]\n\
             [[output]]\nwall = \"floor\"\neye = \"left\"\nregion = [8, 0, 8, 8]\n",
            include_str!("../../../assets/cave.toml")
        );
        let cave = CaveConfig::from_toml_str(&text).unwrap();
        assert_eq!(
            sides_needed(&cave, Side::Mono),
            [Side::Mono, Side::Left, Side::Right]
        );
        assert_eq!(sides_needed(&cave, Side::Left), [Side::Left, Side::Right]);
    }

    #[test]
    fn screenshots_of_outputs_sit_beside_the_main_one() {
        assert_eq!(
            shot_path(Path::new("/tmp/cave.png"), "front-left"),
            PathBuf::from("/tmp/cave.front-left.png")
        );
        assert_eq!(
            shot_path(Path::new("out/c.png"), "floor projector/2"),
            PathBuf::from("out/c.floor_projector_2.png")
        );
    }
}
