//! What the frame pipeline costs (BENCHMARKS.md, issue 12): the real
//! schedule (`ecs::Simulation`), the one every view runs
//! ([`lightcone_engine::ecs::frame_cost`]).
//!
//! * each effect alone, one view of a moving observer, 400 pucks;
//! * frame time per number of views (1, 2, 4: the scene's view, then
//!   alternately its board-frame "truth" and further copies of it), on
//!   the paper's scene and on 1 000 pucks.
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
    let mut thousand = lanes(1000);
    thousand.effects = Effects::default();
    println!("{}", effect_costs(if quick { 50 } else { 400 }, frames));
    println!(
        "{}",
        view_counts(
            &[
                ("paper_carom.toml", paper),
                ("1 000 pucks (lanes)", thousand)
            ],
            if quick { 3 } else { 60 },
        )
    );
}
