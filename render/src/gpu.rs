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

/// Opens a device on `instance`, compatible with `surface` if given.
pub fn open(instance: wgpu::Instance, surface: Option<&wgpu::Surface<'_>>) -> Result<Gpu, String> {
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        force_fallback_adapter: false,
        compatible_surface: surface,
        apply_limit_buckets: false,
    }))
    .map_err(|_| NO_ADAPTER.to_owned())?;
    let info = adapter.get_info();
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("lightcone device"),
        required_features: wgpu::Features::empty(),
        required_limits: wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits()),
        ..Default::default()
    }))
    .map_err(|e| format!("the graphics adapter {} refused a device: {e}", info.name))?;
    Ok(Gpu {
        device,
        queue,
        adapter: format!("{} ({:?})", info.name, info.backend),
        instance,
        handle: adapter,
    })
}
