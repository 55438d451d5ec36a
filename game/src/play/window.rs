//! The window framework, with no game in it: winit's event loop, the wgpu
//! surface of the main window and egui's plumbing (input in, shapes
//! painted over the frame), as wgpu's examples keep their `framework.rs`
//! apart from each example. A [`Game`] says what a frame draws and what
//! the input does. Nothing here is desktop-only (no files, no threads, no
//! second window), so a browser build (winit on the web) starts from it.

use std::sync::Arc;

use lightcone_render::gpu::{self, Gpu};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::window::{Window, WindowId};

use super::ui_paint::UiPainter;

/// What a game run in the window tells the framework after a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    /// Go on: the next frame is requested.
    Continue,
    /// Close the window and end the event loop.
    Exit,
}

/// A game the framework runs: its frames, its input, and the windows it
/// opens besides the main one.
pub trait Game {
    /// The main window's title.
    fn title(&self) -> String;

    /// Called once the GPU instance exists, before the adapter is chosen
    /// (the game's own windows, whose surfaces the adapter must serve).
    fn open_windows(
        &mut self,
        _event_loop: &ActiveEventLoop,
        _instance: &wgpu::Instance,
    ) -> Result<(), String> {
        Ok(())
    }

    /// In a browser: whether to draw with WebGPU where the browser gives
    /// an adapter for it (else WebGL2).
    fn webgpu(&self) -> bool {
        false
    }

    /// Called once the main window and the GPU are ready.
    fn ready(&mut self, gfx: &Gfx) -> Result<(), String>;

    /// Whether the main window's input reaches egui and [`Game::input`]
    /// (a render node shows frames and takes none).
    fn takes_input(&self) -> bool {
        true
    }

    /// An event of the main window (not close, resize or redraw);
    /// `consumed` when egui took it (a click on a panel, typing in a
    /// field).
    fn input(&mut self, gfx: &Gfx, event: &WindowEvent, consumed: bool);

    /// An event of another window the game opened. Returns `None` when
    /// `id` is none of its windows.
    fn other_window(
        &mut self,
        gfx: &Gfx,
        id: WindowId,
        event: &WindowEvent,
    ) -> Option<Result<Flow, String>>;

    /// One frame: the game's time, its views, its panels (through
    /// [`Gfx::run_ui`]) and the pictures drawn into the surface.
    fn frame(&mut self, gfx: &mut Gfx) -> Result<Flow, String>;

    /// Woken between frames by [`wake`] (in a browser: a message from
    /// the lesson's worker), to answer it without waiting for the next
    /// frame.
    fn woken(&mut self) {}
}

/// What wakes the event loop besides the windows' own events.
#[derive(Debug)]
pub enum Wake {
    /// [`wake`] was called: the game answers between frames
    /// ([`Game::woken`]).
    Game,
    /// A screen reader (through AccessKit: AT-SPI on Linux, UI Automation
    /// on Windows, NSAccessibility on macOS) asks for the panel's tree or
    /// for an action on one of its controls. Desktop only: a browser's
    /// canvas has no accessibility tree of its own.
    #[cfg(not(target_arch = "wasm32"))]
    AccessKit(egui_winit::accesskit_winit::Event),
}

#[cfg(not(target_arch = "wasm32"))]
impl From<egui_winit::accesskit_winit::Event> for Wake {
    fn from(event: egui_winit::accesskit_winit::Event) -> Self {
        Self::AccessKit(event)
    }
}

#[cfg(target_arch = "wasm32")]
thread_local! {
    /// Wakes the page's event loop ([`wake`]), once it runs.
    static WAKER: std::cell::RefCell<Option<winit::event_loop::EventLoopProxy<Wake>>> =
        const { std::cell::RefCell::new(None) };
}

/// Asks the event loop to call [`Game::woken`] soon, between frames (in a
/// browser; a no-op elsewhere, and before the loop runs).
pub fn wake() {
    #[cfg(target_arch = "wasm32")]
    WAKER.with(|w| {
        if let Some(proxy) = w.borrow().as_ref() {
            let _ = proxy.send_event(Wake::Game);
        }
    });
}

/// The main window, its surface on the GPU, and egui.
pub struct Gfx {
    /// The window.
    pub window: Arc<Window>,
    /// Its title as last set.
    title: String,
    /// Its surface.
    pub surface: wgpu::Surface<'static>,
    /// The GPU.
    pub gpu: Gpu,
    /// The surface's configuration (size in physical px, format).
    pub config: wgpu::SurfaceConfiguration,
    egui: egui::Context,
    egui_state: egui_winit::State,
    egui_painter: UiPainter,
}

/// The panels of one frame, run but not yet painted.
pub struct Ui(egui::FullOutput);

impl Gfx {
    /// Opens the main window, titled as the game says.
    fn open_window(event_loop: &ActiveEventLoop, game: &impl Game) -> Result<Arc<Window>, String> {
        let title = game.title();
        let attributes = Window::default_attributes().with_title(&title);
        // Shown once its screen-reader adapter is up (AccessKit's rule:
        // the adapter is made before the window is first shown).
        #[cfg(not(target_arch = "wasm32"))]
        let attributes = attributes
            .with_inner_size(winit::dpi::LogicalSize::new(1280.0, 720.0))
            .with_visible(false);
        // In a browser: a canvas appended to the page's body, sized by the
        // page's style sheet (winit follows its size).
        #[cfg(target_arch = "wasm32")]
        let attributes = {
            use winit::platform::web::WindowAttributesExtWebSys;
            attributes.with_append(true)
        };
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| format!("cannot open a window: {e}"))?,
        );
        set_title(&window, &title);
        Ok(window)
    }

    /// Opens the main window, the GPU (Vulkan, else GL), and egui on it,
    /// with its panel's tree offered to screen readers through `proxy`'s
    /// event loop; then shows the window.
    #[cfg(not(target_arch = "wasm32"))]
    fn open(
        event_loop: &ActiveEventLoop,
        game: &mut impl Game,
        proxy: winit::event_loop::EventLoopProxy<Wake>,
    ) -> Result<Self, String> {
        let window = Self::open_window(event_loop, game)?;
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN | wgpu::Backends::GL,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        });
        let surface = instance
            .create_surface(window.clone())
            .map_err(|e| format!("cannot draw into the window: {e}"))?;
        game.open_windows(event_loop, &instance)?;
        let gpu = gpu::open(instance, Some(&surface))?;
        let mut gfx = Self::on_gpu(window, game.title(), surface, gpu)?;
        gfx.egui_state
            .init_accesskit(event_loop, &gfx.window, proxy);
        gfx.window.set_visible(true);
        Ok(gfx)
    }

    /// A screen reader's request: the panel's whole tree (egui then sends
    /// it with every frame's changes), an action on a control (a press, a
    /// focus, a typed value: egui takes it as input at the next frame), or
    /// that no screen reader listens any more.
    #[cfg(not(target_arch = "wasm32"))]
    fn screen_reader(&mut self, event: egui_winit::accesskit_winit::WindowEvent) {
        use egui_winit::accesskit_winit::WindowEvent as Asked;
        match event {
            Asked::InitialTreeRequested => self.egui.enable_accesskit(),
            Asked::ActionRequested(request) => {
                self.egui_state.on_accesskit_action_request(request);
            }
            Asked::AccessibilityDeactivated => self.egui.disable_accesskit(),
        }
        self.window.request_redraw();
    }

    /// In a browser: the GPU of the page's canvas `window`, and egui on
    /// it. WebGL2; or, with `webgpu`, WebGPU where the browser gives an
    /// adapter for it (wgpu's detection: a `navigator.gpu` that gives no
    /// adapter, as Chromium's on Linux without flags, counts as none),
    /// else WebGL2. A future, because WebGPU's adapter and device come
    /// from promises.
    #[cfg(target_arch = "wasm32")]
    async fn open_in_page(
        window: Arc<Window>,
        title: String,
        webgpu: bool,
    ) -> Result<Self, String> {
        let backends = if webgpu {
            wgpu::Backends::BROWSER_WEBGPU | wgpu::Backends::GL
        } else {
            wgpu::Backends::GL
        };
        let instance = wgpu::util::new_instance_with_webgpu_detection(wgpu::InstanceDescriptor {
            backends,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        })
        .await;
        let surface = instance
            .create_surface(window.clone())
            .map_err(|e| format!("cannot draw into the page: {e}"))?;
        let gpu = gpu::open_async(instance, Some(&surface)).await?;
        Self::on_gpu(window, title, surface, gpu)
    }

    /// The surface of `window` configured on `gpu`, and egui on it.
    fn on_gpu(
        window: Arc<Window>,
        title: String,
        surface: wgpu::Surface<'static>,
        gpu: Gpu,
    ) -> Result<Self, String> {
        let size = window.inner_size();
        let mut config = surface
            .get_default_config(&gpu.handle, size.width.max(1), size.height.max(1))
            .ok_or_else(|| format!("the adapter {} cannot draw into this window", gpu.adapter))?;
        let capabilities = surface.get_capabilities(&gpu.handle);
        config.usage |= wgpu::TextureUsages::COPY_SRC & capabilities.usages;
        // In a browser, a plain 8-bit canvas where the page offers one: on
        // WebGL2 wgpu presents an sRGB surface through a full-screen
        // shader pass of its own (a power a pixel), where a plain one is
        // copied; the scene's shader and egui's then encode sRGB
        // themselves (the same pixels). A quarter of a 1280×720 frame
        // under SwiftShader (BENCHMARKS.md, "Frame rate on a software
        // rasteriser").
        #[cfg(target_arch = "wasm32")]
        if let Some(&plain) = capabilities
            .formats
            .iter()
            .find(|&&f| f == config.format.remove_srgb_suffix())
        {
            config.format = plain;
        }
        // Opaque where the surface offers it: a canvas would otherwise
        // blend the picture's alpha with the page behind it.
        if capabilities
            .alpha_modes
            .contains(&wgpu::CompositeAlphaMode::Opaque)
        {
            config.alpha_mode = wgpu::CompositeAlphaMode::Opaque;
        }
        surface.configure(&gpu.device, &config);
        let egui = super::ui_paint::context();
        let egui_state = egui_winit::State::new(
            egui.clone(),
            egui::ViewportId::ROOT,
            &*window,
            Some(window.scale_factor() as f32),
            None,
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        let egui_painter = UiPainter::new(&gpu, config.format);
        Ok(Self {
            window,
            title,
            surface,
            gpu,
            config,
            egui,
            egui_state,
            egui_painter,
        })
    }

    /// The window's new size.
    fn resize(&mut self, size: winit::dpi::PhysicalSize<u32>) {
        self.config.width = size.width.max(1);
        self.config.height = size.height.max(1);
        self.surface.configure(&self.gpu.device, &self.config);
    }

    /// egui's context (what the last frame's panels left in its memory).
    pub fn egui_context(&self) -> &egui::Context {
        &self.egui
    }

    /// The surface's size, physical px.
    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// Runs this frame's panels: `panels` gets egui's root `Ui` (with the
    /// input since the last frame).
    pub fn run_ui(&mut self, panels: impl FnMut(&mut egui::Ui)) -> Ui {
        let raw = self.egui_state.take_egui_input(&self.window);
        Ui(self.egui.run_ui(raw, panels))
    }

    /// The next picture of the surface to draw into; `None` when there is
    /// none this frame (the surface was outdated or lost: it is configured
    /// again, and the next frame draws).
    pub fn next_texture(&mut self) -> Option<wgpu::SurfaceTexture> {
        match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => Some(f),
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&self.gpu.device, &self.config);
                None
            }
            _ => None,
        }
    }

    /// Paints the panels `ui` over what `target` holds (none: a frame
    /// the surface could not give; egui's textures are still brought up
    /// to date), and hands egui's requests (cursor, clipboard) to the
    /// window.
    pub fn paint_ui(&mut self, ui: Ui, target: Option<&wgpu::TextureView>) {
        let Ui(mut output) = ui;
        let platform = std::mem::take(&mut output.platform_output);
        self.egui_state
            .handle_platform_output(&self.window, platform);
        let size = (self.config.width, self.config.height);
        self.egui_painter
            .paint(&self.gpu, &self.egui, output, size, target);
    }
}

/// Titles the window (in a browser, the tab: winit titles only the
/// canvas there).
fn set_title(window: &Window, title: &str) {
    window.set_title(title);
    #[cfg(target_arch = "wasm32")]
    if let Some(document) = web_sys::window().and_then(|w| w.document()) {
        document.set_title(title);
    }
}

/// Opens the event loop, or says how to do without a display.
fn open_event_loop() -> Result<EventLoop<Wake>, String> {
    EventLoop::with_user_event().build().map_err(|e| {
        format!("cannot open a window ({e}); on a machine without a display, use `lightcone render`, or run under Xvfb")
    })
}

/// Opens the window and runs `game` until it exits or the window is
/// closed.
#[cfg(not(target_arch = "wasm32"))]
pub fn run(game: &mut impl Game) -> Result<(), String> {
    let event_loop = open_event_loop()?;
    let mut runner = Runner {
        game,
        gfx: None,
        result: Ok(()),
        proxy: event_loop.create_proxy(),
    };
    event_loop
        .run_app(&mut runner)
        .map_err(|e| format!("the window's event loop failed: {e}"))?;
    runner.result
}

/// Runs `game` in the page (wasm32): the browser drives the event loop,
/// so this returns at once; an error the game returns later is written to
/// the page's console and stops the game.
#[cfg(target_arch = "wasm32")]
pub fn spawn<G: Game + 'static>(game: G) -> Result<(), String> {
    use winit::platform::web::EventLoopExtWebSys;
    let event_loop = open_event_loop()?;
    WAKER.with(|w| *w.borrow_mut() = Some(event_loop.create_proxy()));
    // The game lives as long as the page.
    let game: &'static mut G = Box::leak(Box::new(game));
    event_loop.spawn_app(Runner {
        game,
        gfx: None,
        result: Ok(()),
        opening: Default::default(),
    });
    Ok(())
}

/// The event loop's handler: the window once open, and the first error.
struct Runner<'a, G: Game> {
    game: &'a mut G,
    gfx: Option<Gfx>,
    result: Result<(), String>,
    /// On the desktop: how the screen-reader adapter wakes the loop.
    #[cfg(not(target_arch = "wasm32"))]
    proxy: winit::event_loop::EventLoopProxy<Wake>,
    /// In a browser: the GPU being opened (a future on the page's loop),
    /// and, once it is, the window with it.
    #[cfg(target_arch = "wasm32")]
    opening: Opening,
}

/// The slot a browser's GPU future fills: `None` while it runs.
#[cfg(target_arch = "wasm32")]
type Opening = Option<std::rc::Rc<std::cell::RefCell<Option<Result<Gfx, String>>>>>;

impl<G: Game> Runner<'_, G> {
    /// Takes the window and GPU once open (the game is told it is
    /// ready), or ends the loop with the reason they could not open.
    fn adopt(&mut self, event_loop: &ActiveEventLoop, opened: Result<Gfx, String>) {
        let ready = opened.and_then(|gfx| {
            self.game.ready(&gfx)?;
            Ok(gfx)
        });
        match ready {
            Ok(gfx) => self.gfx = Some(gfx),
            Err(e) => self.obey(event_loop, Err(e)),
        }
    }

    /// Acts on what the game said: an error ends the loop (kept for
    /// [`run`] to return), as does [`Flow::Exit`].
    fn obey(&mut self, event_loop: &ActiveEventLoop, flow: Result<Flow, String>) {
        match flow {
            Ok(Flow::Continue) => {}
            Ok(Flow::Exit) => event_loop.exit(),
            Err(e) => {
                #[cfg(target_arch = "wasm32")]
                web_sys::console::error_1(&format!("lightcone: {e}").into());
                self.result = Err(e);
                event_loop.exit();
            }
        }
    }
}

impl<G: Game> ApplicationHandler<Wake> for Runner<'_, G> {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gfx.is_some() {
            return;
        }
        #[cfg(not(target_arch = "wasm32"))]
        {
            let opened = Gfx::open(event_loop, self.game, self.proxy.clone());
            self.adopt(event_loop, opened);
        }
        #[cfg(target_arch = "wasm32")]
        {
            if self.opening.is_some() {
                return;
            }
            let window = match Gfx::open_window(event_loop, self.game) {
                Ok(window) => window,
                Err(e) => return self.obey(event_loop, Err(e)),
            };
            let slot = std::rc::Rc::new(std::cell::RefCell::new(None));
            self.opening = Some(slot.clone());
            let (title, webgpu) = (self.game.title(), self.game.webgpu());
            wasm_bindgen_futures::spawn_local(async move {
                let opened = Gfx::open_in_page(window.clone(), title, webgpu).await;
                *slot.borrow_mut() = Some(opened);
                // Wakes the loop, which adopts it (`window_event`).
                window.request_redraw();
            });
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, id: WindowId, event: WindowEvent) {
        #[cfg(target_arch = "wasm32")]
        if self.gfx.is_none()
            && let Some(opened) = self
                .opening
                .as_ref()
                .and_then(|slot| slot.borrow_mut().take())
        {
            self.adopt(event_loop, opened);
        }
        let Some(gfx) = self.gfx.as_mut() else { return };
        if id != gfx.window.id() {
            // Keys pressed in another of the game's windows (a CAVE
            // output) reach the game as the main window's do: through
            // its egui input, read with the next frame.
            if matches!(event, WindowEvent::KeyboardInput { .. }) && self.game.takes_input() {
                let _ = gfx.egui_state.on_window_event(&gfx.window, &event);
            }
            if let Some(flow) = self.game.other_window(gfx, id, &event) {
                self.obey(event_loop, flow);
            }
            return;
        }
        // egui sees every event of the main window (a resize too), unless
        // the game takes no input.
        let takes_input = self.game.takes_input();
        let consumed = takes_input && gfx.egui_state.on_window_event(&gfx.window, &event).consumed;
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => gfx.resize(size),
            WindowEvent::RedrawRequested => {
                let flow = self.game.frame(gfx);
                // The title follows the game (a scene or lesson opened from
                // the menu, a file dropped on the page).
                let title = self.game.title();
                if title != gfx.title {
                    set_title(&gfx.window, &title);
                    gfx.title = title;
                }
                self.obey(event_loop, flow);
            }
            event if takes_input => self.game.input(gfx, &event, consumed),
            _ => {}
        }
    }

    fn user_event(&mut self, _event_loop: &ActiveEventLoop, wake: Wake) {
        if self.gfx.is_none() {
            return;
        }
        match wake {
            Wake::Game => self.game.woken(),
            #[cfg(not(target_arch = "wasm32"))]
            Wake::AccessKit(event) => {
                if let Some(gfx) = self.gfx.as_mut()
                    && event.window_id == gfx.window.id()
                {
                    gfx.screen_reader(event.window_event);
                }
            }
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(gfx) = &self.gfx {
            gfx.window.request_redraw();
        }
    }
}
