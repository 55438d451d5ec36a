//! Rendering without a window: into a texture, read back, written as PNG.

use std::io::Write;
use std::path::Path;

use super::frame::{self, Camera, FrameVertex, ViewKind};
use super::gpu::Gpu;
use super::pipeline::{Renderer, SAMPLES};
use lightcone_engine::ecs::{Entity, Simulation};
use lightcone_engine::scene::Scene;

/// The colour format of headless images (sRGB, 8 bits per channel).
pub const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// The background: a dark room.
pub const BACKGROUND: wgpu::Color = wgpu::Color {
    r: 0.01,
    g: 0.01,
    b: 0.015,
    a: 1.0,
};

/// An RGBA8 image.
pub struct Image {
    /// Width, px.
    pub width: u32,
    /// Height, px.
    pub height: u32,
    /// Rows top to bottom, 4 bytes a pixel.
    pub rgba: Vec<u8>,
}

impl Image {
    /// The pixel at (x, y), RGBA.
    #[must_use]
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 4] {
        let i = 4 * (y as usize * self.width as usize + x as usize);
        [
            self.rgba[i],
            self.rgba[i + 1],
            self.rgba[i + 2],
            self.rgba[i + 3],
        ]
    }

    /// The image as a PNG file's bytes (RGBA, 8 bits a channel).
    pub fn png_bytes(&self) -> Result<Vec<u8>, String> {
        let mut bytes = Vec::new();
        let mut encoder = png::Encoder::new(&mut bytes, self.width, self.height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(|e| e.to_string())?;
        writer
            .write_image_data(&self.rgba)
            .and_then(|()| writer.finish())
            .map_err(|e| e.to_string())?;
        Ok(bytes)
    }

    /// Writes a PNG.
    pub fn save_png(&self, path: &Path) -> Result<(), String> {
        // Encoded in memory, then written in one checked write: a buffered
        // file writer would drop the error of its last flush (a full disk).
        let bytes = self
            .png_bytes()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        write_file(path, &bytes)
    }

    /// Reads a PNG written by [`Self::save_png`].
    pub fn load_png(path: &Path) -> Result<Self, String> {
        let file = std::fs::File::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
        decoder.set_transformations(png::Transformations::EXPAND);
        let mut reader = decoder
            .read_info()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let size = reader
            .output_buffer_size()
            .ok_or_else(|| format!("{}: image too large", path.display()))?;
        let mut buf = vec![0; size];
        let info = reader
            .next_frame(&mut buf)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        if info.color_type != png::ColorType::Rgba || info.bit_depth != png::BitDepth::Eight {
            return Err(format!("{}: not an 8-bit RGBA PNG", path.display()));
        }
        buf.truncate(info.buffer_size());
        Ok(Self {
            width: info.width,
            height: info.height,
            rgba: buf,
        })
    }
}

/// A texture to draw into and the buffer it is read back through, reused
/// from frame to frame: what any windowless picture is drawn onto.
pub struct Target {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    readback: wgpu::Buffer,
    padded: u32,
    width: u32,
    height: u32,
}

impl Target {
    /// A `width × height` target of [`FORMAT`] on `gpu`.
    #[must_use]
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Self {
        Self::with_format(gpu, width, height, FORMAT)
    }

    /// A `width × height` target of `format` (4 bytes a texel, RGBA
    /// order: `Rgba8Unorm` or `Rgba8UnormSrgb`) on `gpu`.
    #[must_use]
    pub fn with_format(gpu: &Gpu, width: u32, height: u32, format: wgpu::TextureFormat) -> Self {
        let device = &gpu.device;
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("headless target"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let padded = padded_row(width);
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("headless readback"),
            size: u64::from(padded) * u64::from(height),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Self {
            texture,
            view,
            readback,
            padded,
            width,
            height,
        }
    }

    /// The view to draw into.
    #[must_use]
    pub fn view(&self) -> &wgpu::TextureView {
        &self.view
    }

    /// Its size, (width, height) px.
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Copies the texture out (after what `encoder` holds) and reads the
    /// image back, waiting for the GPU.
    pub fn read(&self, gpu: &Gpu, mut encoder: wgpu::CommandEncoder) -> Result<Image, String> {
        let (width, height, padded) = (self.width, self.height, self.padded);
        record_copy(
            &mut encoder,
            &self.texture,
            &self.readback,
            padded,
            (width, height),
        );
        gpu.queue.submit([encoder.finish()]);
        let rgba = read_rows(gpu, &self.readback, padded, width, height)?;
        Ok(Image {
            width,
            height,
            rgba,
        })
    }
}

/// An offscreen target with its renderer, reused from frame to frame.
pub struct Offscreen {
    target: Target,
    renderer: Renderer,
}

impl Offscreen {
    /// A `width × height` target on `gpu`.
    #[must_use]
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Self {
        Self::with(gpu, width, height, FORMAT, SAMPLES)
    }

    /// A `width × height` target of `format` ([`Target::with_format`]) on
    /// `gpu`, drawn with `samples` samples a pixel: what a window on
    /// another adapter or in a browser draws (`Gpu::window_samples`).
    #[must_use]
    pub fn with(
        gpu: &Gpu,
        width: u32,
        height: u32,
        format: wgpu::TextureFormat,
        samples: u32,
    ) -> Self {
        Self {
            target: Target::with_format(gpu, width, height, format),
            renderer: Renderer::new(&gpu.device, format, width, height, samples),
        }
    }

    /// Draws `vertices` with `camera` and reads the image back.
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        vertices: &[FrameVertex],
        camera: &Camera,
    ) -> Result<Image, String> {
        let (width, height) = self.target.size();
        let view_proj = camera.view_proj(width as f32 / height as f32);
        self.draw_with(gpu, vertices, view_proj)
    }

    /// Draws `vertices` (eye-relative, observer's frame) with any
    /// view-projection matrix, such as a CAVE wall's off-axis one, and reads
    /// the image back.
    pub fn draw_with(
        &mut self,
        gpu: &Gpu,
        vertices: &[FrameVertex],
        view_proj: glam::Mat4,
    ) -> Result<Image, String> {
        let device = &gpu.device;
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("headless frame"),
        });
        self.renderer.render(
            device,
            &gpu.queue,
            &mut encoder,
            self.target.view(),
            super::pipeline::Draw {
                vertices,
                view_proj,
                clear: Some(BACKGROUND),
                viewport: None,
            },
        );
        self.target.read(gpu, encoder)
    }
}

/// Bytes in a row of a `width`-texel, 4-byte-texel image copied out of a
/// texture: `4 × width`, padded to wgpu's copy alignment (256).
#[must_use]
pub fn padded_row(width: u32) -> u32 {
    (4 * width).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT
}

/// Records into `encoder` a copy of `texture` (`size` = width × height px,
/// 4 bytes a texel) into `buffer`, in rows of `padded` bytes.
pub fn record_copy(
    encoder: &mut wgpu::CommandEncoder,
    texture: &wgpu::Texture,
    buffer: &wgpu::Buffer,
    padded: u32,
    size: (u32, u32),
) {
    let (width, height) = size;
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
}

/// A new readable buffer for a copy of a `size` (width × height px) image
/// and its padded row length ([`padded_row`]), the copy of `texture` into
/// it recorded in `encoder` ([`record_copy`]): a window's frame for a
/// screenshot.
#[must_use]
pub fn copy_to_buffer(
    gpu: &Gpu,
    texture: &wgpu::Texture,
    size: (u32, u32),
    encoder: &mut wgpu::CommandEncoder,
) -> (wgpu::Buffer, u32) {
    let padded = padded_row(size.0);
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("frame readback"),
        size: u64::from(padded) * u64::from(size.1),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    record_copy(encoder, texture, &buffer, padded, size);
    (buffer, padded)
}

/// The `height` rows of `4 × width` bytes of a mapped copy whose rows are
/// `padded` bytes long.
#[must_use]
pub fn unpad(data: &[u8], padded: u32, width: u32, height: u32) -> Vec<u8> {
    let mut rgba = Vec::with_capacity((4 * width * height) as usize);
    for row in 0..height {
        let start = (row * padded) as usize;
        rgba.extend_from_slice(&data[start..start + (4 * width) as usize]);
    }
    rgba
}

/// Makes texels copied out of a surface of `format` opaque RGBA in place:
/// BGRA surfaces (most desktop ones) swapped,
/// alpha set to 255 (what the window shows).
pub fn opaque_rgba(texels: &mut [u8], format: wgpu::TextureFormat) {
    let bgra = matches!(
        format,
        wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
    );
    for px in texels.chunks_mut(4) {
        if bgra {
            px.swap(0, 2);
        }
        px[3] = 255;
    }
}

/// Waits for the GPU, maps `buffer` (rows of `padded` bytes) and returns
/// its `height` rows of `4 × width` bytes, unpadded.
pub fn read_rows(
    gpu: &Gpu,
    buffer: &wgpu::Buffer,
    padded: u32,
    width: u32,
    height: u32,
) -> Result<Vec<u8>, String> {
    let slice = buffer.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    gpu.device
        .poll(wgpu::PollType::Wait {
            submission_index: None,
            timeout: None,
        })
        .map_err(|e| format!("the GPU did not finish: {e}"))?;
    rx.recv()
        .map_err(|e| format!("readback lost: {e}"))?
        .map_err(|e| format!("readback failed: {e}"))?;
    let data = slice
        .get_mapped_range()
        .map_err(|e| format!("readback failed: {e}"))?;
    let rgba = unpad(&data, padded, width, height);
    drop(data);
    buffer.unmap();
    Ok(rgba)
}

/// Draws `vertices` with `camera` into a `width × height` image.
pub fn draw(
    gpu: &Gpu,
    vertices: &[FrameVertex],
    camera: &Camera,
    width: u32,
    height: u32,
) -> Result<Image, String> {
    Offscreen::new(gpu, width, height).draw(gpu, vertices, camera)
}

/// Renders what observer `observer` of `scene` sees at board time `t`,
/// its camera framed as [`frame::scene_view`] says (the whole table unless
/// the scene names a `look_at`).
pub fn render_scene(
    gpu: &Gpu,
    scene: &Scene,
    t: f64,
    observer: usize,
    kind: ViewKind,
    width: u32,
    height: u32,
) -> Result<Image, String> {
    let aspect = f64::from(width) / f64::from(height);
    let (mut sim, view) = frame::scene_view(scene, observer, t, kind, aspect);
    render_view(gpu, &mut sim, view, width, height)
}

/// Renders what `view` of `sim` saw at its last frame (its `Apparent`,
/// drawn with its camera), headless.
pub fn render_view(
    gpu: &Gpu,
    sim: &mut Simulation,
    view: Entity,
    width: u32,
    height: u32,
) -> Result<Image, String> {
    let meshes = frame::ViewMeshes::new(sim);
    let (Some(apparent), Some(camera)) = (sim.apparent(view), sim.camera(view)) else {
        return Err("no such view".into());
    };
    let mut vertices = Vec::new();
    frame::build_view(apparent, &meshes, &mut vertices);
    draw(gpu, &vertices, &camera.into(), width, height)
}

/// Writes `bytes` to the file at `path` (created or truncated), reporting
/// every failure, including those a buffered writer would drop on close
/// (a full disk, `/dev/full`).
fn write_file(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let mut f = std::fs::File::create(path)
        .map_err(|e| format!("{}: cannot create: {e}", path.display()))?;
    f.write_all(bytes)
        .and_then(|()| f.flush())
        .map_err(|e| format!("{}: cannot write: {e}", path.display()))
}
