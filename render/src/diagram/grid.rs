//! The diagram's grid: lines at a round step (0.5, 1, 2, 5, 10, … m or s)
//! chosen so that a range holds at most `MAX_LINES` of them, every line
//! or every other one labelled with its value and unit.

use super::{GRID_RGB, Mark, Place, Role};

/// Most grid lines across one axis of a diagram.
pub const MAX_LINES: usize = 16;
/// Most labelled lines along one axis.
pub const MAX_LABELS: usize = 8;

/// The grid along one axis of the diagram.
#[derive(Clone, Debug, PartialEq)]
pub struct GridAxis {
    /// The step between lines (m or s): 0.5 × 10ⁿ, 1 × 10ⁿ or 2 × 10ⁿ… of
    /// the sequence 0.5, 1, 2, 5, 10, 20, 50, …
    pub step: f64,
    /// The lines' values in the range, increasing.
    pub lines: Vec<f64>,
    /// Label every this many lines (1 or 2), from the even multiples.
    pub label_every: usize,
}

impl GridAxis {
    /// The grid over `range` (m or s): the smallest step of the sequence
    /// whose multiples in the range number at most `MAX_LINES`; no lines
    /// where the numbers are too large for a step to change them (a
    /// diagram at board time −10¹⁸ s: the count stays bounded).
    #[must_use]
    pub fn over(range: (f64, f64)) -> Self {
        let width = range.1 - range.0;
        let mut step = 0.5;
        while width.is_finite() && width / step > MAX_LINES as f64 - 1.0 && step < 1e300 {
            step *= if (step / 10f64.powf(step.log10().floor()) - 2.0).abs() < 1e-9 {
                2.5
            } else {
                2.0
            };
        }
        let first = (range.0 / step).ceil();
        let last = (range.1 / step).floor();
        let count = last - first + 1.0;
        let lines = if count.is_finite() && count > 0.0 && count <= MAX_LINES as f64 {
            (0..count as usize)
                .map(|k| (first + k as f64) * step)
                .collect()
        } else {
            Vec::new()
        };
        let label_every = if lines.len() > MAX_LABELS { 2 } else { 1 };
        Self {
            step,
            lines,
            label_every,
        }
    }

    /// The values labelled: every line, or the even multiples of the step.
    pub fn labelled(&self) -> impl Iterator<Item = f64> + '_ {
        let every = self.label_every as f64;
        self.lines
            .iter()
            .copied()
            .filter(move |v| ((v / self.step).round() / every).fract() == 0.0)
    }
}

/// `v` (m or s) as a label's number: at most two decimals, no trailing
/// zeros, no "−0".
#[must_use]
pub fn label_text(v: f64) -> String {
    let text = format!("{v:.2}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_owned()
    } else {
        text.to_owned()
    }
}

/// Pushes the grid's lines and labels over `ranges` (x in m, t in s) onto
/// `marks`: a line at each of `across`'s values from the bottom to the top,
/// one at each of `up`'s from left to right, the labels under the bottom
/// edge (m) and left of the left edge (s).
pub(super) fn marks(
    marks: &mut Vec<Mark>,
    (across, up): (&GridAxis, &GridAxis),
    (x, t): ((f64, f64), (f64, f64)),
) {
    let line = |points| Mark::Line {
        role: Role::Grid,
        points,
        rgb: GRID_RGB,
        width: 1.0,
        alpha: 1.0,
        dashed: false,
    };
    for &g in &across.lines {
        marks.push(line(vec![(g, t.0), (g, t.1)]));
    }
    for &g in &up.lines {
        marks.push(line(vec![(x.0, g), (x.1, g)]));
    }
    let label = |at, text, place| Mark::Label {
        role: Role::GridLabel,
        at,
        text,
        place,
        rgb: [175, 175, 185],
    };
    for g in across.labelled() {
        marks.push(label(
            (g, t.0),
            format!("{} m", label_text(g)),
            Place::Below,
        ));
    }
    for g in up.labelled() {
        marks.push(label((x.0, g), format!("{} s", label_text(g)), Place::Left));
    }
}
