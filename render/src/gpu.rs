//! Adapter and device. Works on Mesa's software drivers (lavapipe through
//! Vulkan, llvmpipe through GL), which is what CI has.

/// What to install when there is no adapter at all.
pub const NO_ADAPTER: &str = "no graphics adapter found: install Mesa's software Vulkan driver \
     (Debian/Ubuntu: apt-get install mesa-vulkan-drivers) or a GPU driver";

/// A device and its queue, with the adapter's name for reports.
pub struct Gpu {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Adapter name and backend, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan)".
    pub adapter: String,
    /// The instance (kept for surfaces).
    pub instance: wgpu::Instance,
    /// The adapter (for surface configuration).
    pub handle: wgpu::Adapter,
}

impl Gpu {
    /// Samples a pixel for a window's scene: one on a software rasteriser
    /// (lavapipe, llvmpipe, a browser's SwiftShader: a CPU adapter), where
    /// 4× MSAA made each frame of a 1280×720 page about four times the
    /// pixel work (187–192 ms a frame in headless Chromium, 5 fps:
    /// BENCHMARKS.md, "Frame rate on a software rasteriser"), and
    /// [`crate::pipeline::SAMPLES`] on a GPU. Pictures written to files keep
    /// [`crate::pipeline::SAMPLES`] (their cost is not a frame rate).
    #[must_use]
    pub fn window_samples(&self) -> u32 {
        if self.handle.get_info().device_type == wgpu::DeviceType::Cpu {
            1
        } else {
            crate::pipeline::SAMPLES
        }
    }
}

/// Opens the best available adapter (a software one is fine) without a
/// window: Vulkan first (lavapipe on CI), then GL (llvmpipe). Fails with
/// [`NO_ADAPTER`] when there is none.
pub fn headless() -> Result<Gpu, String> {
    let mut last = NO_ADAPTER.to_owned();
    for backends in [wgpu::Backends::VULKAN, wgpu::Backends::GL] {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        });
        match open(instance, None) {
            Ok(gpu) => return Ok(gpu),
            Err(e) => last = e,
        }
    }
    Err(last)
}

/// Opens a device on `instance`, compatible with `surface` if given,
/// waiting for the adapter and the device (pollster). Not for a browser's
/// WebGPU, whose requests are promises the page's own loop resolves: there,
/// [`open_async`].
pub fn open(instance: wgpu::Instance, surface: Option<&wgpu::Surface<'_>>) -> Result<Gpu, String> {
    pollster::block_on(open_async(instance, surface))
}

/// [`open`], as a future: what a browser awaits (WebGPU's adapter and
/// device come from promises; WebGL2's and every native backend's are
/// ready at once, so [`open`] blocks on this same future).
///
/// # Errors
///
/// No adapter (the message says what to install), or a device the adapter
/// refuses (the adapter named).
pub async fn open_async(
    instance: wgpu::Instance,
    surface: Option<&wgpu::Surface<'_>>,
) -> Result<Gpu, String> {
    let adapter = instance
        .request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: surface,
            apply_limit_buckets: false,
        })
        .await
        .map_err(|_| NO_ADAPTER.to_owned())?;
    let info = adapter.get_info();
    let (device, queue) = adapter
        .request_device(&wgpu::DeviceDescriptor {
            label: Some("lightcone device"),
            required_features: wgpu::Features::empty(),
            required_limits: limits().using_resolution(adapter.limits()),
            ..Default::default()
        })
        .await
        .map_err(|e| format!("the graphics adapter {} refused a device: {e}", info.name))?;
    Ok(Gpu {
        device,
        queue,
        adapter: format!("{} ({:?})", info.name, info.backend),
        instance,
        handle: adapter,
    })
}

/// The limits asked of the device: WebGL2's in a browser, else wgpu's
/// downlevel defaults.
fn limits() -> wgpu::Limits {
    if cfg!(target_arch = "wasm32") {
        wgpu::Limits::downlevel_webgl2_defaults()
    } else {
        wgpu::Limits::downlevel_defaults()
    }
}

/// A private runtime directory to give Mesa's Vulkan device-select layer,
/// or `None` when the environment's `XDG_RUNTIME_DIR` will do.
///
/// The layer (`VK_LAYER_MESA_device_select`, an implicit layer) asks the
/// Wayland compositor for the default GPU each time an instance enumerates
/// its adapters, through libwayland-client's `wl_display_connect`, which
/// prints `error: XDG_RUNTIME_DIR is invalid or not set in the environment.`
/// when that variable is unset or not an absolute path (as under
/// `xvfb-run`, `su` or CI): twice per instance, on stderr. With
/// `XDG_RUNTIME_DIR` set to the directory returned here
/// (`$TMPDIR/lightcone-runtime-UID`, created mode 0700 if missing, owned by
/// this user) the connection fails quietly (no compositor socket there)
/// and the layer falls back to X11 or the first adapter, as before.
///
/// Returns `None` when `XDG_RUNTIME_DIR` is an absolute path to a directory
/// closed to others (nothing to do), or when the private directory exists
/// but is not this user's or is open to others (left alone: the warning
/// stays). Setting the variable is the caller's: it must happen before
/// anything else in the process reads the environment concurrently (the
/// CLI: first thing in `main`; Python: through `os.environ`).
#[cfg(unix)]
#[must_use]
pub fn private_runtime_dir() -> Option<std::path::PathBuf> {
    use std::os::unix::fs::{DirBuilderExt, MetadataExt, PermissionsExt};
    let valid = std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|d| {
        std::path::Path::new(&d).is_absolute()
            && std::fs::metadata(&d)
                .is_ok_and(|m| m.is_dir() && m.permissions().mode() & 0o077 == 0)
    });
    if valid {
        return None;
    }
    let uid = std::fs::metadata("/proc/self").map_or(0, |m| m.uid());
    let dir = std::env::temp_dir().join(format!("lightcone-runtime-{uid}"));
    let _ = std::fs::DirBuilder::new().mode(0o700).create(&dir);
    let ours = std::fs::metadata(&dir)
        .is_ok_and(|m| m.is_dir() && m.uid() == uid && m.permissions().mode() & 0o077 == 0);
    ours.then_some(dir)
}

/// Not Unix: no Mesa device-select layer to quieten.
#[cfg(not(unix))]
#[must_use]
pub fn private_runtime_dir() -> Option<std::path::PathBuf> {
    None
}
