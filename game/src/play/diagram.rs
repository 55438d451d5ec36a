//! The live space-time diagram's window (key Y): whose frame's lines of
//! simultaneity to draw and which board axis runs across, the plot, and its
//! legend. What is drawn is [`lightcone_render::diagram::plot_with`]'s list
//! of marks and keys, the one `lightcone diagram` rasterises into its PNG:
//! this file only paints them with egui.

use lightcone_render::diagram::{
    Area, Axis, BACKGROUND, CROSS, EVENT_RADIUS, Key, LABEL_PX, Mark, Options, Place, Swatch,
    dashes, plot_with,
};

use super::actions::{Overlay, UiAction};
use crate::model::GameState;

/// The plot's height in the window, points.
const PLOT_HEIGHT: f32 = 300.0;

/// Where the last frame drew the diagram's data (for the screenshot's
/// sidecar and tests): the data area in physical px from the window's top
/// left, and the board x (or y, m) and time (s) it spans.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placed {
    /// The data area, physical px ([`lightcone_render::diagram::Plot::to_px`]
    /// maps into it).
    pub area: Area,
    /// The board axis' range across, m.
    pub x: (f64, f64),
    /// The board time's range up, s.
    pub t: (f64, f64),
}

fn placed_id() -> egui::Id {
    egui::Id::unique("lightcone diagram placed")
}

/// Where the diagram was drawn in the frame just run on `ctx`, if it was.
pub fn placed(ctx: &egui::Context) -> Option<Placed> {
    ctx.data(|d| d.get_temp(placed_id()))
}

/// The diagram's window, its top left at `at` (points); closing it asks
/// for [`Overlay::Diagram`]'s toggle.
pub fn window(
    ctx: &egui::Context,
    state: &mut GameState,
    at: egui::Pos2,
    actions: &mut Vec<UiAction>,
) {
    let mut open = true;
    ctx.data_mut(|d| d.remove::<Placed>(placed_id()));
    egui::Window::new("space-time diagram")
        .open(&mut open)
        .default_pos(at)
        .default_width(600.0)
        .show(ctx, |ui| {
            frame_and_axis(ui, state);
            plot(ui, state);
        });
    if !open {
        actions.push(UiAction::Toggle(Overlay::Diagram));
    }
}

/// A row of two combo boxes: the frame (none or a puck) and the axis.
pub fn frame_and_axis(ui: &mut egui::Ui, state: &mut GameState) {
    ui.horizontal(|ui| {
        let name = |i: Option<usize>| match i.and_then(|i| state.scene.pucks.get(i)) {
            Some(p) => format!("{}'s frame", p.name),
            None => "board frame only".to_owned(),
        };
        let mut frame = state.show.diagram_frame;
        egui::ComboBox::from_id_salt("diagram frame")
            .selected_text(name(frame))
            .show_ui(ui, |ui| {
                ui.selectable_value(&mut frame, None, name(None));
                for i in 0..state.scene.pucks.len() {
                    ui.selectable_value(&mut frame, Some(i), name(Some(i)));
                }
            });
        state.show.diagram_frame = frame;
        ui.label("across:");
        ui.selectable_value(&mut state.show.diagram_axis, Axis::X, "x");
        ui.selectable_value(&mut state.show.diagram_axis, Axis::Y, "y");
    });
}

fn colour(rgb: [u8; 3], alpha: f64) -> egui::Color32 {
    egui::Color32::from_rgba_unmultiplied(rgb[0], rgb[1], rgb[2], (alpha * 255.0).round() as u8)
}

fn pos((x, y): (f64, f64)) -> egui::Pos2 {
    egui::pos2(x as f32, y as f32)
}

/// The diagram for the eye looked through at the time shown, then its
/// legend.
fn plot(ui: &mut egui::Ui, state: &GameState) {
    let options = Options {
        axis: state.show.diagram_axis,
        frame: state.show.diagram_frame,
    };
    let p = plot_with(&state.scene, state.physics(), state.eye().event, options);
    let size = egui::vec2(ui.available_width().max(360.0), PLOT_HEIGHT);
    let (rect, _) = ui.allocate_exact_size(size, egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 0.0, colour(BACKGROUND, 1.0));
    let area = Area {
        left: f64::from(rect.left()),
        top: f64::from(rect.top()),
        width: f64::from(rect.width()),
        height: f64::from(rect.height()),
    }
    .inside_margins();
    let px = |q| pos(p.to_px(area, q));
    let font = egui::FontId::proportional(LABEL_PX as f32);
    for mark in &p.marks {
        match mark {
            Mark::Line {
                points,
                rgb,
                width,
                alpha,
                dashed,
                ..
            } => {
                let stroke = egui::Stroke::new(*width as f32, colour(*rgb, *alpha));
                let pts: Vec<(f64, f64)> = points.iter().map(|&q| p.to_px(area, q)).collect();
                let pieces = if *dashed { dashes(&pts) } else { vec![pts] };
                for piece in pieces {
                    let piece = piece.into_iter().map(pos).collect();
                    painter.add(egui::Shape::line(piece, stroke));
                }
            }
            Mark::Cross { at } => cross(&painter, px(*at)),
            Mark::Event { at, rgb, .. } => {
                painter.circle_filled(px(*at), EVENT_RADIUS as f32 + 2.0, egui::Color32::WHITE);
                painter.circle_filled(px(*at), EVENT_RADIUS as f32, colour(*rgb, 1.0));
            }
            Mark::Label {
                at,
                text,
                place,
                rgb,
                ..
            } => {
                let (anchor, offset) = match place {
                    Place::Below => (egui::Align2::CENTER_TOP, egui::vec2(0.0, 4.0)),
                    Place::Left => (egui::Align2::RIGHT_CENTER, egui::vec2(-6.0, 0.0)),
                };
                painter.text(
                    px(*at) + offset,
                    anchor,
                    text,
                    font.clone(),
                    colour(*rgb, 1.0),
                );
            }
        }
    }
    let ppp = f64::from(ui.ctx().pixels_per_point());
    let shown = Placed {
        area: Area {
            left: area.left * ppp,
            top: area.top * ppp,
            width: area.width * ppp,
            height: area.height * ppp,
        },
        x: p.x,
        t: p.t,
    };
    ui.ctx().data_mut(|d| d.insert_temp(placed_id(), shown));
    legend(ui, &p.legend);
}

fn cross(painter: &egui::Painter, q: egui::Pos2) {
    let s = CROSS as f32;
    let stroke = egui::Stroke::new(2.0, egui::Color32::WHITE);
    painter.line_segment([q + egui::vec2(-s, -s), q + egui::vec2(s, s)], stroke);
    painter.line_segment([q + egui::vec2(-s, s), q + egui::vec2(s, -s)], stroke);
}

/// The keys in two columns (down the first, then the second, as in the
/// PNG), each a swatch of the mark and its meaning at [`LABEL_PX`].
fn legend(ui: &mut egui::Ui, keys: &[Key]) {
    let rows = keys.len().div_ceil(2);
    egui::Grid::new("diagram legend")
        .num_columns(4)
        .spacing(egui::vec2(6.0, 3.0))
        .show(ui, |ui| {
            for row in 0..rows {
                for key in [keys.get(row), keys.get(row + rows)].into_iter().flatten() {
                    swatch(ui, key);
                    ui.label(egui::RichText::new(&key.text).size(LABEL_PX as f32));
                }
                ui.end_row();
            }
        });
}

/// A key's swatch, 26 × 14 points.
fn swatch(ui: &mut egui::Ui, key: &Key) {
    let (rect, _) = ui.allocate_exact_size(egui::vec2(26.0, 14.0), egui::Sense::hover());
    let painter = ui.painter_at(rect.expand(2.0));
    let (l, r, y) = (rect.left(), rect.right(), rect.center().y);
    let c = colour(key.rgb, 1.0);
    match key.swatch {
        Swatch::Line => {
            painter.line_segment(
                [egui::pos2(l, y), egui::pos2(r, y)],
                egui::Stroke::new(2.5, c),
            );
        }
        Swatch::Dashed => {
            for piece in dashes(&[(f64::from(l), f64::from(y)), (f64::from(r), f64::from(y))]) {
                let piece = piece.into_iter().map(pos).collect();
                painter.add(egui::Shape::line(piece, egui::Stroke::new(2.0, c)));
            }
        }
        Swatch::Dot => {
            painter.circle_filled(
                rect.center(),
                EVENT_RADIUS as f32 + 2.0,
                egui::Color32::WHITE,
            );
            painter.circle_filled(rect.center(), EVENT_RADIUS as f32, c);
        }
        Swatch::Cross => cross(&painter, rect.center()),
    }
}
