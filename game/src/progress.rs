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

/// A bar over `total` steps of a long command (a benchmark's sections,
/// frames, files), naming the step under way. Like [`bar`], drawn on
/// stderr only when it is a terminal.
pub fn steps(total: u64, what: &str) -> Steps {
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    let style = ProgressStyle::with_template(&format!(
        "{{elapsed_precise}} [{{bar:40}}] {{pos}}/{{len}} {what}: {{msg}}"
    ))
    .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    // Redraw the elapsed time while one long step runs.
    bar.enable_steady_tick(std::time::Duration::from_millis(250));
    Steps { bar }
}

/// A bar over whole steps.
pub struct Steps {
    bar: ProgressBar,
}

impl Steps {
    /// Names the step now under way.
    pub fn step(&self, message: &str) {
        self.bar.set_message(message.to_owned());
    }

    /// One step done.
    pub fn inc(&self) {
        self.bar.inc(1);
    }

    /// Runs `f` (which prints to the terminal) with the bar hidden, so
    /// printed lines and the bar do not overwrite each other.
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        self.bar.suspend(f)
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Drop for Steps {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}
