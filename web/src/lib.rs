//! The browser build's entry point: `scripts/web.sh` compiles this crate
//! for `wasm32-unknown-unknown` and runs `wasm-bindgen` on it. On native
//! targets it is empty.
#![cfg(target_arch = "wasm32")]

use wasm_bindgen::prelude::*;

/// Starts the game on the page's canvas (`#lightcone`): the scene named
/// by `?scene=NAME` (a shipped scene, `.toml` optional), else the default.
#[wasm_bindgen(start)]
pub fn start() -> Result<(), JsValue> {
    // A panic reaches the page's console (and so the browser test).
    std::panic::set_hook(Box::new(|info| {
        web_sys::console::error_1(&JsValue::from_str(&format!("lightcone panicked: {info}")));
    }));
    let search = web_sys::window()
        .and_then(|w| w.location().search().ok())
        .unwrap_or_default();
    let scene = web_sys::UrlSearchParams::new_with_str(&search)
        .ok()
        .and_then(|p| p.get("scene"));
    lightcone::play::web_app::start(scene.as_deref()).map_err(|e| JsValue::from_str(&e))
}
