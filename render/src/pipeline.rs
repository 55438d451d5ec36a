//! The scene pipeline: one render pass, flat-shaded triangles with depth.
//! GPU state lives here; the device and queue are passed in (tests hand in
//! their own).

use bytemuck::{Pod, Zeroable};
use glam::Mat4;

use super::frame::FrameVertex;

/// Depth buffer format.
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Samples per pixel (MSAA) on a GPU, and for pictures written to files;
/// 4 is supported by every WebGPU adapter for renderable colour formats
/// and for the depth format. A window on a software rasteriser draws one
/// ([`crate::gpu::Gpu::window_samples`]).
pub const SAMPLES: u32 = 4;

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct CameraUniform {
    view_proj: [[f32; 4]; 4],
    light: [f32; 4],
}

/// What one pass draws.
#[derive(Clone, Copy, Debug)]
pub struct Draw<'a> {
    /// A triangle list.
    pub vertices: &'a [FrameVertex],
    /// Camera: view and projection.
    pub view_proj: Mat4,
    /// Background colour; `None` keeps what the target holds (a second
    /// view drawn beside the first).
    pub clear: Option<wgpu::Color>,
    /// The part of the target to draw into, `[x, y, width, height]` in
    /// pixels; `None` for all of it.
    pub viewport: Option<[f32; 4]>,
}

/// The scene renderer for one colour format and image size.
pub struct Renderer {
    pipeline: wgpu::RenderPipeline,
    camera: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    vertices: wgpu::Buffer,
    capacity: u64,
    depth: wgpu::TextureView,
    /// The multisampled colour target, resolved into the caller's target
    /// after each pass (and kept, so a second view drawn beside the first
    /// loads it); `None` with one sample a pixel, which draws straight into
    /// the caller's target.
    colour: Option<wgpu::TextureView>,
    format: wgpu::TextureFormat,
    size: (u32, u32),
    samples: u32,
}

fn colour_view(
    device: &wgpu::Device,
    format: wgpu::TextureFormat,
    (width, height): (u32, u32),
    samples: u32,
) -> Option<wgpu::TextureView> {
    if samples == 1 {
        return None;
    }
    let view = device
        .create_texture(&wgpu::TextureDescriptor {
            label: Some("scene colour (multisampled)"),
            size: wgpu::Extent3d {
                width: width.max(1),
                height: height.max(1),
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: samples,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        })
        .create_view(&wgpu::TextureViewDescriptor::default());
    Some(view)
}

fn depth_view(
    device: &wgpu::Device,
    (width, height): (u32, u32),
    samples: u32,
) -> wgpu::TextureView {
    device
        .create_texture(&wgpu::TextureDescriptor {
            label: Some("scene depth"),
            size: wgpu::Extent3d {
                width: width.max(1),
                height: height.max(1),
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: samples,
            dimension: wgpu::TextureDimension::D2,
            format: DEPTH,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        })
        .create_view(&wgpu::TextureViewDescriptor::default())
}

fn vertex_buffer(device: &wgpu::Device, capacity: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("scene vertices"),
        size: capacity * std::mem::size_of::<FrameVertex>() as u64,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// A linear colour as a target that stores values as given holds it
/// (sRGB's encoding, IEC 61966-2-1; alpha as is).
fn encoded(c: wgpu::Color) -> wgpu::Color {
    let encode = |x: f64| {
        if x <= 0.003_130_8 {
            12.92 * x
        } else {
            1.055 * x.powf(1.0 / 2.4) - 0.055
        }
    };
    wgpu::Color {
        r: encode(c.r),
        g: encode(c.g),
        b: encode(c.b),
        a: c.a,
    }
}

impl Renderer {
    /// A renderer drawing into `format` targets of `width × height`, with
    /// `samples` samples a pixel (1, or [`SAMPLES`]). Colours are linear:
    /// an sRGB `format` encodes them as it stores them, any other is given
    /// them encoded.
    #[must_use]
    pub fn new(
        device: &wgpu::Device,
        format: wgpu::TextureFormat,
        width: u32,
        height: u32,
        samples: u32,
    ) -> Self {
        let shader = device.create_shader_module(wgpu::include_wgsl!("scene.wgsl"));
        let camera = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("scene camera"),
            size: std::mem::size_of::<CameraUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scene camera layout"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene camera bind group"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: camera.as_entire_binding(),
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("scene pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let attributes =
            wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32, 3 => Float32];
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("scene pipeline"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: std::mem::size_of::<FrameVertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &attributes,
                })],
            },
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::TriangleList,
                cull_mode: None,
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: wgpu::MultisampleState {
                count: samples,
                ..Default::default()
            },
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some(if format.is_srgb() {
                    "fs_main"
                } else {
                    "fs_main_encoded"
                }),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let capacity = 4096;
        Self {
            pipeline,
            camera,
            bind_group,
            vertices: vertex_buffer(device, capacity),
            capacity,
            depth: depth_view(device, (width, height), samples),
            colour: colour_view(device, format, (width, height), samples),
            format,
            size: (width, height),
            samples,
        }
    }

    /// The image size drawn into.
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// Follows a new target size.
    pub fn resize(&mut self, device: &wgpu::Device, width: u32, height: u32) {
        if (width, height) != self.size {
            self.size = (width, height);
            self.depth = depth_view(device, self.size, self.samples);
            self.colour = colour_view(device, self.format, self.size, self.samples);
        }
    }

    /// Records a pass that clears `target` and draws the triangles.
    pub fn render(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        draw: Draw<'_>,
    ) {
        let Draw {
            vertices,
            view_proj,
            clear,
            viewport,
        } = draw;
        if vertices.len() as u64 > self.capacity {
            self.capacity = (vertices.len() as u64).next_power_of_two();
            self.vertices = vertex_buffer(device, self.capacity);
        }
        if vertices.is_empty() && clear.is_none() {
            return;
        }
        // With nothing to draw, a pass that clears only (a wall the eye is
        // behind shows the background, not what the target held).
        if !vertices.is_empty() {
            queue.write_buffer(&self.vertices, 0, bytemuck::cast_slice(vertices));
        }
        let uniform = CameraUniform {
            view_proj: view_proj.to_cols_array_2d(),
            light: [0.3, -0.4, 1.0, 0.0],
        };
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(&uniform));
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("scene pass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: self.colour.as_ref().unwrap_or(target),
                depth_slice: None,
                resolve_target: self.colour.as_ref().map(|_| target),
                ops: wgpu::Operations {
                    load: clear.map_or(wgpu::LoadOp::Load, |c| {
                        wgpu::LoadOp::Clear(if self.format.is_srgb() { c } else { encoded(c) })
                    }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if vertices.is_empty() {
            return;
        }
        if let Some([x, y, w, h]) = viewport {
            pass.set_viewport(x, y, w, h, 0.0, 1.0);
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.draw(0..vertices.len() as u32, 0..1);
    }
}
