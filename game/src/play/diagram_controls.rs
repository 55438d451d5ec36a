//! The space-time diagram window's controls: whose frame's lines of
//! simultaneity to draw, and which board axis runs across.

use lightcone_render::diagram::Axis;

use crate::model::GameState;

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
