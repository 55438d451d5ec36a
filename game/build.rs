//! Points the `lightcone` binary and the tests at the libpython they were
//! linked against (an rpath), so a binary built with pyenv's Python does not
//! load the system's libpython of the same name at run time.

fn main() {
    // The browser build (wasm32) embeds no Python.
    if std::env::var("CARGO_CFG_TARGET_ARCH").as_deref() != Ok("wasm32") {
        pyo3_build_config::add_libpython_rpath_link_args();
    }
}
