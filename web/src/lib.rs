//! The browser build's entry point: `scripts/web.sh` compiles this crate
//! for `wasm32-unknown-unknown` and runs `wasm-bindgen` on it. On native
//! targets it is empty.
#![cfg(target_arch = "wasm32")]

use wasm_bindgen::prelude::*;

/// Starts the game on the page's canvas: the scene file the link's
/// fragment carries (`#scene=DATA`), else the shipped scene named by
/// `?scene=NAME` (`.toml` optional), else the default, at `?at=T` if given,
/// drawn with WebGL2 (or WebGPU with `?gpu=webgpu`, where the browser has
/// it); `?lesson=NAME` or `#lesson=DATA` starts a lesson (its Python in a
/// Web Worker), `?drive=FPS` plays it with nobody at the page (see
/// `lightcone::links` and `lightcone::play::web_app::start`).
#[wasm_bindgen(start)]
pub fn start() -> Result<(), JsValue> {
    // A panic reaches the page's console (and so the browser test).
    std::panic::set_hook(Box::new(|info| {
        web_sys::console::error_1(&JsValue::from_str(&format!("lightcone panicked: {info}")));
    }));
    let location = web_sys::window().map(|w| w.location());
    let search = location
        .as_ref()
        .and_then(|l| l.search().ok())
        .unwrap_or_default();
    let fragment = location
        .as_ref()
        .and_then(|l| l.hash().ok())
        .unwrap_or_default();
    let query = web_sys::UrlSearchParams::new_with_str(&search).ok();
    let scene = query.as_ref().and_then(|p| p.get("scene"));
    let lesson = query.as_ref().and_then(|p| p.get("lesson"));
    let at = query.as_ref().and_then(|p| p.get("at"));
    let gpu = query.as_ref().and_then(|p| p.get("gpu"));
    let drive = query.as_ref().and_then(|p| p.get("drive"));
    let address = lightcone::play::web_app::Address {
        scene: scene.as_deref(),
        lesson: lesson.as_deref(),
        at: at.as_deref(),
        fragment: &fragment,
        gpu: gpu.as_deref(),
        drive: drive.as_deref(),
    };
    lightcone::play::web_app::start(&address).map_err(|e| JsValue::from_str(&e))
}

/// A file dropped on the page (`index.html`'s `drop` handler): a scene
/// (`.toml`) opens at the next frame, with `lightcone check`'s located
/// errors in the scene menu when it has any. `text` is `undefined` for a
/// file larger than [`max_dropped_bytes`], which the page does not read.
#[wasm_bindgen]
pub fn drop_file(name: String, text: Option<String>) {
    lightcone::play::web_app::drop_file(name, text);
}

/// Largest file the page reads when one is dropped on it, bytes.
#[wasm_bindgen]
pub fn max_dropped_bytes() -> u32 {
    u32::try_from(lightcone::play::web_app::MAX_DROPPED).unwrap_or(u32::MAX)
}
