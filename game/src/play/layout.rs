//! Where the pictures go in the window: the area the panels leave, the
//! desktop pictures side by side in it, or the CAVE walls tiled in a grid.

use lightcone_tracker::cave::CaveConfig;

use crate::model::Pane;

/// How one rectangle of the window is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plan {
    /// A desktop picture (a view of an eye: seen or truth).
    Desktop(Pane),
    /// CAVE wall `i`, from the head's midpoint.
    Wall(usize),
}

/// The area the panels left for the pictures at the last frame: its left
/// and right edges, physical px (both 0 before the first frame: the whole
/// window).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SceneArea {
    /// Left edge, physical px.
    pub left: f32,
    /// Right edge, physical px.
    pub right: f32,
}

impl SceneArea {
    /// The left edge and width of the area in a window `w` wide.
    pub fn span(self, w: f32) -> (f32, f32) {
        let right = if self.right > self.left {
            self.right.min(w)
        } else {
            w
        };
        (self.left, right - self.left)
    }

    /// The desktop pictures' rectangles in a `w × h` window.
    pub fn rects(self, panes: &[Pane], w: f32, h: f32) -> Vec<([f32; 4], Pane)> {
        let (left, width) = self.span(w);
        layout(panes, left, width, h)
    }

    /// What each rectangle of a `w × h` window shows: the CAVE's tiled
    /// walls, or the desktop pictures `panes`.
    pub fn plans(
        self,
        cave: Option<&CaveConfig>,
        panes: &[Pane],
        w: f32,
        h: f32,
    ) -> Vec<([f32; 4], Plan)> {
        let (left, width) = self.span(w);
        match cave {
            Some(c) => wall_tiles(c, &tiled_walls(c), left, width, h),
            None => layout(panes, left, width, h)
                .into_iter()
                .map(|(r, p)| (r, Plan::Desktop(p)))
                .collect(),
        }
    }
}

/// `rect` cut to the `w × h` surface (wgpu refuses viewports outside it);
/// `None` when nothing is left.
pub fn clamp_rect(rect: [f32; 4], w: f32, h: f32) -> Option<[f32; 4]> {
    let (x0, y0) = (rect[0].max(0.0), rect[1].max(0.0));
    let (x1, y1) = ((rect[0] + rect[2]).min(w), (rect[1] + rect[3]).min(h));
    (x1 - x0 >= 1.0 && y1 - y0 >= 1.0).then_some([x0, y0, x1 - x0, y1 - y0])
}

/// The walls the main window tiles in a CAVE: those no output shows; all
/// of them (a preview) when every wall has an output.
pub fn tiled_walls(cave: &CaveConfig) -> Vec<usize> {
    let unmapped = cave.unmapped_walls();
    if unmapped.is_empty() {
        (0..cave.walls.len()).collect()
    } else {
        unmapped
    }
}

/// The CAVE walls tiled in a grid over `[x0, x0 + w] × [0, h]`, each tile
/// keeping its wall's aspect ratio.
pub fn wall_tiles(
    cave: &CaveConfig,
    walls: &[usize],
    x0: f32,
    w: f32,
    h: f32,
) -> Vec<([f32; 4], Plan)> {
    let n = walls.len().max(1);
    let cols = (n as f32).sqrt().ceil() as usize;
    let rows = n.div_ceil(cols);
    let (tw, th) = (
        w.max(cols as f32) / cols as f32,
        h.max(rows as f32) / rows as f32,
    );
    walls
        .iter()
        .enumerate()
        .map(|(i, &index)| {
            let wall = &cave.walls[index];
            let aspect = (wall.width() / wall.height()) as f32;
            let (mut rw, mut rh) = ((tw - 4.0).max(1.0), (th - 4.0).max(1.0));
            if rw / rh > aspect {
                rw = rh * aspect;
            } else {
                rh = rw / aspect;
            }
            let (cx, cy) = (
                x0 + tw * ((i % cols) as f32 + 0.5),
                th * ((i / cols) as f32 + 0.5),
            );
            (
                [cx - rw / 2.0, cy - rh / 2.0, rw.max(1.0), rh.max(1.0)],
                Plan::Wall(index),
            )
        })
        .collect()
}

/// The rectangles (x, y, w, h in physical px) of the pictures `panes`,
/// side by side in equal widths, left to right, in the area
/// `[x0, x0 + w] × [0, h]` left free by the panels.
pub fn layout(panes: &[Pane], x0: f32, w: f32, h: f32) -> Vec<([f32; 4], Pane)> {
    let (w, h) = (w.max(1.0), h.max(1.0));
    let n = panes.len().max(1) as f32;
    panes
        .iter()
        .enumerate()
        .map(|(k, &p)| ([x0 + w * k as f32 / n, 0.0, w / n, h], p))
        .collect()
}
