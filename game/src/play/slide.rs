//! The game's picture without a window, for `render` and `record` (a
//! teacher's slides): the window's views drawn by the window's scene
//! renderer, and over them the window's own overlays (rings, names,
//! clocks with their dials, trails, ghosts, arrows, collision arcs,
//! captions, the magnifier, the hints) painted by the window's egui
//! painter, onto an offscreen target read back as an image. The panels
//! (controls, lesson) are left out: the pictures fill the whole image.

use lightcone_render::gpu::Gpu;
use lightcone_render::headless::{self, Image, Target};

use super::layout::SceneArea;
use super::pictures::Pictures;
use super::shown::aspect;
use super::ui_paint::UiPainter;
use crate::model::{GameState, Pane};

/// Window pixels per egui point at 720 px of height (the window's own
/// scale under Xvfb): a taller slide scales its labels with it, up to
/// 4 (a 2880 px-high slide), so text keeps its share of the picture.
const POINTS_HEIGHT: f32 = 720.0;

/// What a slide draws over its pictures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Overlays {
    /// The window's overlays, as the window draws them.
    Shown,
    /// The bare pictures (`--no-overlays`).
    Hidden,
}

/// A windowless picture of the game, reused frame after frame.
pub struct Slide {
    target: Target,
    pictures: Pictures,
    egui: egui::Context,
    painter: UiPainter,
}

impl Slide {
    /// A `width × height` slide on `gpu`.
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Self {
        let egui = super::ui_paint::context();
        Self {
            target: Target::new(gpu, width, height),
            // A picture for a file: 4 samples a pixel on any adapter.
            pictures: Pictures::new(
                gpu,
                headless::FORMAT,
                (width, height),
                lightcone_render::pipeline::SAMPLES,
            ),
            egui,
            painter: UiPainter::new(gpu, headless::FORMAT),
        }
    }

    /// Draws `state` now: runs its frame schedule for the slide's
    /// pictures, draws them, paints the overlays over them (unless
    /// `overlays` hides them), and reads the image back.
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        state: &mut GameState,
        overlays: Overlays,
    ) -> Result<Image, String> {
        let size = self.target.size();
        let (w, h) = (size.0 as f32, size.1 as f32);
        let area = self.area();
        let panes: Vec<(Pane, f64)> = area
            .rects(&state.pane_list(), w, h)
            .into_iter()
            .map(|(r, p)| (p, aspect(r)))
            .collect();
        state.run_frame(&panes);
        let plans = area.plans(None, &state.pane_list(), w, h);
        self.pictures
            .draw(gpu, self.target.view(), size, &plans, state, None);
        if overlays == Overlays::Shown {
            let ppp = (h / POINTS_HEIGHT).clamp(1.0, 4.0);
            let output = self.egui.run_ui(raw_input(size, ppp), |ui| {
                super::overlay::layer(ui.ctx(), state, 0.0, w, h);
            });
            self.painter
                .paint(gpu, &self.egui, output, size, Some(self.target.view()));
        }
        let encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("slide readback"),
            });
        self.target.read(gpu, encoder)
    }
}

impl Slide {
    /// What the overlays drew on the last slide (labels, the magnifier),
    /// for its layout sidecar ([`super::screenshot::save_layout`]).
    pub fn drawn(&self) -> super::overlay::Drawn {
        super::overlay::drawn(&self.egui)
    }

    /// The room the pictures take: the whole slide.
    pub fn area(&self) -> SceneArea {
        SceneArea {
            left: 0.0,
            right: self.target.size().0 as f32,
        }
    }
}

/// egui's input for one slide: no events, a screen of `size` physical px
/// at `ppp` pixels per point.
fn raw_input(size: (u32, u32), ppp: f32) -> egui::RawInput {
    let mut raw = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(size.0 as f32 / ppp, size.1 as f32 / ppp),
        )),
        ..Default::default()
    };
    raw.viewports
        .entry(egui::ViewportId::ROOT)
        .or_default()
        .native_pixels_per_point = Some(ppp);
    raw
}
