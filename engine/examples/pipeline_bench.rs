//! What the frame pipeline costs (BENCHMARKS.md, issue 12): the real
//! schedule (`ecs::Simulation`), the one every view runs
//! ([`lightcone_engine::ecs::frame_cost`]).
//!
//! * each effect alone, one view of a moving observer, 400 pucks;
//! * frame time per number of views (1, 2, 4: the scene's view, then
//!   alternately its board-frame "truth" and further copies of it), on
//!   the paper's scene, on 1 000 and on 10 000 pucks.
//!
//! `cargo run --release -p lightcone-engine --example pipeline_bench [--quick]`
//! prints the Markdown tables (`lightcone bench optics` prints them too).

use lightcone_engine::ecs::frame_cost::{effect_costs, lanes, view_counts};
use lightcone_engine::scene::{self, Effects};

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let frames = if quick { 5 } else { 120 };
    let paper_path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/scenes/paper_carom.toml"
    );
    let paper = match scene::load(std::path::Path::new(paper_path)) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    let sizes: &[usize] = if quick { &[100, 200] } else { &[1000, 10_000] };
    let names: Vec<String> = sizes.iter().map(|n| format!("{n} pucks (lanes)")).collect();
    let mut scenes = vec![("paper_carom.toml", paper)];
    for (name, &n) in names.iter().zip(sizes) {
        let mut s = lanes(n);
        s.effects = Effects::default();
        scenes.push((name, s));
    }
    println!("{}", effect_costs(if quick { 50 } else { 400 }, frames));
    println!("{}", view_counts(&scenes, if quick { 3 } else { 30 }));
}
