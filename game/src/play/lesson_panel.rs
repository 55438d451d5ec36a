//! The lesson's panel: its text, the open question with a button per
//! choice, its charts, the claims it checked, and — when it failed — its
//! traceback, with a reload button.

use egui::{Color32, RichText};

use std::time::Duration;

use super::actions::UiAction;
use lightcone_lesson::{Bars, LessonUi};

/// What the panel shows of a lesson host: the desktop's (a lesson in its
/// own process, or in the game's) and the browser's (in a Web Worker).
pub trait LessonStatus {
    /// The lesson's name, for the heading (its file's name).
    fn title(&self) -> String;
    /// The hook out and how long it has run.
    fn hook_running(&self) -> Option<(&'static str, Duration)>;
    /// Longest a hook may run.
    fn limit(&self) -> Duration;
    /// Why the lesson stopped, if it did.
    fn error(&self) -> Option<&str>;
    /// What the lesson put on screen, lent to `f`.
    fn screen(&self, f: &mut dyn FnMut(&LessonUi));
    /// What the lesson waits for before its first hook (Python starting
    /// in the browser), if anything.
    fn starting(&self) -> Option<String> {
        None
    }
}

/// Draws the panel for `host`; clicks become `actions` (applied after the
/// frame's UI).
pub fn show(ui: &mut egui::Ui, host: &dyn LessonStatus, actions: &mut Vec<UiAction>) {
    let name = host.title();
    ui.horizontal(|ui| {
        ui.heading(format!("Lesson: {name}"));
        if ui.button("reload (F5)").clicked() {
            actions.push(UiAction::ReloadLesson);
        }
    });
    ui.separator();
    egui::ScrollArea::vertical().show(ui, |ui| {
        if let Some((hook, running)) = host.hook_running()
            && running.as_secs_f64() > 0.25
        {
            ui.colored_label(
                Color32::LIGHT_YELLOW,
                format!(
                    "{hook} running {:.1} s (board time waits; stopped at {} s)",
                    running.as_secs_f64(),
                    host.limit().as_secs_f64()
                ),
            );
            ui.separator();
        }
        if let Some(waiting) = host.starting() {
            ui.colored_label(Color32::LIGHT_YELLOW, waiting);
            ui.separator();
        }
        if let Some(error) = host.error() {
            ui.colored_label(
                Color32::from_rgb(255, 110, 110),
                "The lesson stopped with an error. The game keeps its last state; fix the file and save (it reloads), or press reload.",
            );
            ui.add(
                egui::Label::new(
                    RichText::new(error)
                        .monospace()
                        .color(Color32::from_rgb(255, 170, 170)),
                )
                .wrap(),
            );
            ui.separator();
        }
        host.screen(&mut |lesson| contents(ui, lesson, actions));
    });
}

/// A check mark (held) or a cross (failed), drawn with strokes: the
/// default fonts have no ✔/✘ glyphs, which rendered as empty boxes.
fn mark(ui: &mut egui::Ui, ok: bool, colour: Color32) {
    let size = egui::vec2(14.0, 14.0);
    let (rect, _) = ui.allocate_exact_size(size, egui::Sense::hover());
    let p = |x: f32, y: f32| rect.min + egui::vec2(x * rect.width(), y * rect.height());
    let stroke = egui::Stroke::new(2.2, colour);
    let painter = ui.painter();
    if ok {
        painter.line_segment([p(0.1, 0.55), p(0.4, 0.85)], stroke);
        painter.line_segment([p(0.4, 0.85), p(0.9, 0.15)], stroke);
    } else {
        painter.line_segment([p(0.15, 0.15), p(0.85, 0.85)], stroke);
        painter.line_segment([p(0.85, 0.15), p(0.15, 0.85)], stroke);
    }
}

fn contents(ui: &mut egui::Ui, lesson: &LessonUi, actions: &mut Vec<UiAction>) {
    if !lesson.text.is_empty() {
        ui.label(RichText::new(&lesson.text).size(15.0));
        ui.separator();
    }
    if let Some(q) = &lesson.question {
        ui.label(RichText::new(&q.text).strong().color(Color32::LIGHT_YELLOW));
        match q.chosen {
            None => {
                ui.label("Time is paused: predict, then choose.");
                for (i, choice) in q.choices.iter().enumerate() {
                    if ui.button(choice).clicked() {
                        actions.push(UiAction::Answer(i));
                    }
                }
            }
            Some(i) => {
                let chosen = &q.choices[i];
                match q.answer {
                    Some(a) if a == i => {
                        ui.colored_label(Color32::LIGHT_GREEN, format!("{chosen}: right."));
                    }
                    Some(a) => {
                        ui.colored_label(
                            Color32::LIGHT_RED,
                            format!("{chosen}: not quite; the answer is {}.", q.choices[a]),
                        );
                    }
                    None => {
                        ui.label(format!("You chose {chosen}."));
                    }
                }
            }
        }
        ui.separator();
    }
    for chart in &lesson.bars {
        bars(ui, chart);
    }
    if !lesson.claims.is_empty() {
        ui.label("checked:");
        for c in &lesson.claims {
            let colour = if c.ok {
                Color32::LIGHT_GREEN
            } else {
                Color32::LIGHT_RED
            };
            ui.horizontal_wrapped(|ui| {
                mark(ui, c.ok, colour);
                ui.colored_label(colour, &c.claim);
            });
            if !c.detail.is_empty() {
                ui.small(&c.detail);
            }
        }
    }
    if !lesson.printed.is_empty() {
        ui.separator();
        ui.collapsing("printed", |ui| {
            let start = lesson.printed.len().saturating_sub(12);
            for line in &lesson.printed[start..] {
                ui.label(RichText::new(line).monospace().small());
            }
        });
    }
    if let Some(msg) = lesson.closing() {
        ui.separator();
        ui.colored_label(Color32::LIGHT_GREEN, format!("Lesson complete. {msg}"));
    } else if lesson.finished.is_some() {
        ui.separator();
        ui.colored_label(
            Color32::LIGHT_YELLOW,
            "Watch the table: the light of what happened is still on its way to your eye.",
        );
    }
}

/// A bar chart with the expected values as a line over it.
fn bars(ui: &mut egui::Ui, chart: &Bars) {
    ui.label(RichText::new(&chart.title).strong());
    let width = ui.available_width().max(100.0);
    let (rect, _) = ui.allocate_exact_size(egui::vec2(width, 140.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, Color32::from_gray(30));
    let top = chart
        .counts
        .iter()
        .chain(chart.expected.iter().flatten())
        .fold(0.0f64, |m, &x| m.max(x))
        .max(1e-300);
    let (lo, hi) = (chart.edges[0], chart.edges[chart.edges.len() - 1]);
    let span = (hi - lo).max(1e-300);
    let x = |v: f64| rect.left() + ((v - lo) / span) as f32 * rect.width();
    let y = |v: f64| rect.bottom() - (v / top) as f32 * (rect.height() - 4.0);
    for (i, &c) in chart.counts.iter().enumerate() {
        let r = egui::Rect::from_min_max(
            egui::pos2(x(chart.edges[i]) + 1.0, y(c)),
            egui::pos2(x(chart.edges[i + 1]) - 1.0, rect.bottom()),
        );
        painter.rect_filled(r, 0.0, Color32::from_rgb(90, 150, 230));
    }
    if let Some(expected) = &chart.expected {
        let points: Vec<egui::Pos2> = expected
            .iter()
            .enumerate()
            .map(|(i, &e)| egui::pos2(x((chart.edges[i] + chart.edges[i + 1]) / 2.0), y(e)))
            .collect();
        painter.add(egui::Shape::line(
            points,
            egui::Stroke::new(2.0, Color32::from_rgb(255, 200, 80)),
        ));
    }
    ui.small(format!("{lo:.3} … {hi:.3}; line: expected"));
}

#[cfg(not(target_arch = "wasm32"))]
impl LessonStatus for crate::lesson::LessonHost {
    fn title(&self) -> String {
        self.path().file_name().map_or_else(
            || self.path().display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        )
    }

    fn hook_running(&self) -> Option<(&'static str, Duration)> {
        crate::lesson::LessonHost::hook_running(self)
    }

    fn limit(&self) -> Duration {
        self.limit
    }

    fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    fn screen(&self, f: &mut dyn FnMut(&LessonUi)) {
        self.with_ui(|ui| f(ui));
    }
}
