//! Progress bars for long commands (indicatif), drawn on stderr only when it
//! is a terminal, so pipes and test logs stay clean.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// A bar from 0 to `total` (in `unit`s; fractional totals are shown in
/// thousandths).
pub fn bar(total: f64, unit: &str) -> Bar {
    let scale = 1000.0;
    let bar = ProgressBar::with_draw_target(
        Some((total.max(0.0) * scale) as u64),
        ProgressDrawTarget::stderr(),
    );
    let style = ProgressStyle::with_template(&format!(
        "{{elapsed_precise}} [{{bar:40}}] {{msg}} / {total} {unit} (eta {{eta}})"
    ))
    .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    Bar { bar, scale }
}

/// A bar over a fractional quantity.
pub struct Bar {
    bar: ProgressBar,
    scale: f64,
}

impl Bar {
    /// Sets the position.
    pub fn set_position_f64(&self, x: f64) {
        self.bar.set_position((x.max(0.0) * self.scale) as u64);
        self.bar.set_message(format!("{x:.3}"));
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
