//! egui's shapes painted over a picture: the one painter of the window's
//! panels and of the windowless slides (`render`, `record`). It keeps
//! egui's textures (the font atlas, images) on the GPU from frame to
//! frame, as egui's own deltas say.

use lightcone_render::gpu::Gpu;

/// The egui context of every window and slide, with the game's visuals:
/// the side panels have no fill of their own. Under them is the picture's
/// background (the scene's clear colour, `(25, 25, 33)` against egui's
/// panel grey `(27, 27, 27)`), so a fill there only covered it again; on a
/// software rasteriser that fill was half of the pixels egui shades (the
/// panel 236 000 of 461 000 at 1280×720), and egui's pixels are most of a
/// frame's cost there (BENCHMARKS.md, "Frame rate on a software
/// rasteriser").
#[must_use]
pub fn context() -> egui::Context {
    let egui = egui::Context::default();
    egui.all_styles_mut(|style| style.visuals.panel_fill = egui::Color32::TRANSPARENT);
    egui
}

/// egui's wgpu renderer for targets of one format.
pub struct UiPainter {
    renderer: egui_wgpu::Renderer,
}

impl UiPainter {
    /// A painter for targets of `format` on `gpu`.
    pub fn new(gpu: &Gpu, format: wgpu::TextureFormat) -> Self {
        Self {
            renderer: egui_wgpu::Renderer::new(&gpu.device, format, Default::default()),
        }
    }

    /// Paints `output` (one egui pass of `egui`, its platform output
    /// already handed to the window, if any) over what `target` holds, a
    /// picture of `size` physical px. With no target (a frame the surface
    /// could not give) egui's textures are still brought up to date, so
    /// the next frame's text has its glyphs.
    pub fn paint(
        &mut self,
        gpu: &Gpu,
        egui: &egui::Context,
        output: egui::FullOutput,
        size: (u32, u32),
        target: Option<&wgpu::TextureView>,
    ) {
        let jobs = egui.tessellate(output.shapes, output.pixels_per_point);
        let (device, queue) = (&gpu.device, &gpu.queue);
        for (id, deltas) in &output.textures_delta.set {
            for delta in deltas {
                self.renderer.update_texture(device, queue, *id, delta);
            }
        }
        if let Some(target) = target {
            let screen = egui_wgpu::ScreenDescriptor {
                size_in_pixels: [size.0, size.1],
                pixels_per_point: output.pixels_per_point,
            };
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("egui"),
            });
            self.renderer
                .update_buffers(device, queue, &mut encoder, &jobs, &screen);
            {
                let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("egui pass"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: target,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Load,
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    depth_stencil_attachment: None,
                    timestamp_writes: None,
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                self.renderer
                    .render(&mut pass.forget_lifetime(), &jobs, &screen);
            }
            queue.submit([encoder.finish()]);
        }
        for id in &output.textures_delta.free {
            self.renderer.free_texture(id);
        }
    }
}
