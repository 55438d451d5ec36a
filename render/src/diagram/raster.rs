//! The diagram's CPU painter: a [`Plot`]'s marks, labels and legend into an
//! [`Image`] (`lightcone diagram`, Python's `diagram`). Lines are
//! antialiased by their distance to each pixel; text is egui's own font
//! (Ubuntu Light) rasterised by `ab_glyph`.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};
use lightcone_engine::physics::Billiard;
use lightcone_engine::scene::Scene;
use lightcone_engine::spacetime::Event;

use super::{
    Area, BACKGROUND, CROSS, EVENT_RADIUS, Key, LABEL_PX, Mark, Options, Place, Plot, Simultaneity,
    Swatch, dashes,
};
use crate::headless::Image;

/// The legend's rows' height in the image, px.
const ROW_PX: f64 = 22.0;
/// The smallest image that has room for the legend under the plot, px.
const LEGEND_FROM: (u32, u32) = (480, 360);

/// An image being painted, with one line's coverage at a time.
struct Canvas {
    img: Image,
    /// Coverage (0–1) of the line being drawn, per pixel.
    mask: Vec<f32>,
    /// The pixels the mask has touched.
    touched: Vec<usize>,
}

impl Canvas {
    fn new(width: u32, height: u32) -> Self {
        let [r, g, b] = BACKGROUND;
        let n = width as usize * height as usize;
        Self {
            img: Image {
                width,
                height,
                rgba: [r, g, b, 255].repeat(n),
            },
            mask: vec![0.0; n],
            touched: Vec::new(),
        }
    }

    /// Mixes `rgb` into pixel (x, y) by `alpha`; nothing off the image.
    fn blend(&mut self, x: i64, y: i64, rgb: [u8; 3], alpha: f64) {
        if x < 0 || y < 0 || x >= i64::from(self.img.width) || y >= i64::from(self.img.height) {
            return;
        }
        let i = 4 * (y as usize * self.img.width as usize + x as usize);
        for (px, &new) in self.img.rgba[i..i + 3].iter_mut().zip(&rgb) {
            let old = f64::from(*px);
            *px = (old + (f64::from(new) - old) * alpha.clamp(0.0, 1.0)).round() as u8;
        }
    }

    /// Adds segment `a`–`b` (px), `width` px wide, to the mask.
    fn cover(&mut self, a: (f64, f64), b: (f64, f64), width: f64) {
        let r = (width / 2.0).max(0.5);
        let (w, h) = (f64::from(self.img.width), f64::from(self.img.height));
        if ![a.0, a.1, b.0, b.1].iter().all(|v| v.is_finite()) {
            return;
        }
        let x0 = (a.0.min(b.0) - r - 1.0).floor().max(0.0);
        let x1 = (a.0.max(b.0) + r + 1.0).ceil().min(w - 1.0);
        let y0 = (a.1.min(b.1) - r - 1.0).floor().max(0.0);
        let y1 = (a.1.max(b.1) + r + 1.0).ceil().min(h - 1.0);
        if x0 > x1 || y0 > y1 {
            return;
        }
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len2 = dx * dx + dy * dy;
        for y in y0 as usize..=y1 as usize {
            for x in x0 as usize..=x1 as usize {
                let (px, py) = (x as f64, y as f64);
                let s = if len2 > 0.0 {
                    (((px - a.0) * dx + (py - a.1) * dy) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let d = (px - a.0 - s * dx).hypot(py - a.1 - s * dy);
                let coverage = (r + 0.5 - d).clamp(0.0, 1.0) as f32;
                if coverage > 0.0 {
                    let i = y * self.img.width as usize + x;
                    if self.mask[i] == 0.0 {
                        self.touched.push(i);
                    }
                    self.mask[i] = self.mask[i].max(coverage);
                }
            }
        }
    }

    /// Paints the mask in `rgb` at `alpha` and clears it.
    fn flush(&mut self, rgb: [u8; 3], alpha: f64) {
        let width = self.img.width as usize;
        for i in std::mem::take(&mut self.touched) {
            let coverage = f64::from(self.mask[i]);
            self.mask[i] = 0.0;
            self.blend(
                (i % width) as i64,
                (i / width) as i64,
                rgb,
                alpha * coverage,
            );
        }
    }

    /// A polyline (px), dashed or not, in one stroke.
    fn polyline(
        &mut self,
        points: &[(f64, f64)],
        width: f64,
        rgb: [u8; 3],
        alpha: f64,
        dashed: bool,
    ) {
        if dashed {
            for piece in dashes(points) {
                for pair in piece.windows(2) {
                    self.cover(pair[0], pair[1], width);
                }
            }
        } else {
            for pair in points.windows(2) {
                self.cover(pair[0], pair[1], width);
            }
        }
        self.flush(rgb, alpha);
    }

    fn disc(&mut self, c: (f64, f64), r: f64, rgb: [u8; 3]) {
        self.cover(c, c, 2.0 * r);
        self.flush(rgb, 1.0);
    }

    fn cross(&mut self, p: (f64, f64)) {
        let s = CROSS;
        self.cover((p.0 - s, p.1 - s), (p.0 + s, p.1 + s), 2.0);
        self.cover((p.0 - s, p.1 + s), (p.0 + s, p.1 - s), 2.0);
        self.flush([255, 255, 255], 1.0);
    }
}

/// Text in egui's font.
struct Pen<'f> {
    font: FontRef<'f>,
    scale: PxScale,
}

impl Pen<'_> {
    fn new() -> Self {
        let font = FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT)
            .unwrap_or_else(|_| unreachable!("egui's built-in font parses"));
        // ab_glyph's scale is the font's ascent-to-descent height; egui's
        // size is smaller by its line gap: this matches LABEL_PX points.
        Self {
            font,
            scale: PxScale::from((LABEL_PX * 1.15) as f32),
        }
    }

    /// How wide `text` is, px.
    fn width(&self, text: &str) -> f64 {
        let scaled = self.font.as_scaled(self.scale);
        let mut w = 0.0;
        let mut prev = None;
        for ch in text.chars() {
            let id = self.font.glyph_id(ch);
            if let Some(p) = prev {
                w += scaled.kern(p, id);
            }
            w += scaled.h_advance(id);
            prev = Some(id);
        }
        f64::from(w)
    }

    /// `text` with its top left at `(x, y)` px.
    fn write(&self, cv: &mut Canvas, text: &str, (x, y): (f64, f64), rgb: [u8; 3]) {
        let scaled = self.font.as_scaled(self.scale);
        let mut caret = x as f32;
        let baseline = y as f32 + scaled.ascent();
        let mut prev = None;
        for ch in text.chars() {
            let id = self.font.glyph_id(ch);
            if let Some(p) = prev {
                caret += scaled.kern(p, id);
            }
            let glyph = id.with_scale_and_position(self.scale, point(caret, baseline));
            caret += scaled.h_advance(id);
            prev = Some(id);
            if let Some(outline) = self.font.outline_glyph(glyph) {
                let b = outline.px_bounds();
                outline.draw(|gx, gy, coverage| {
                    let px = (b.min.x as i64) + i64::from(gx);
                    let py = (b.min.y as i64) + i64::from(gy);
                    cv.blend(px, py, rgb, f64::from(coverage));
                });
            }
        }
    }
}

/// Paints `plot` into `area` of `cv`: every mark, back to front.
fn paint_marks(cv: &mut Canvas, pen: &Pen, plot: &Plot, area: Area) {
    for mark in &plot.marks {
        match mark {
            Mark::Line {
                points,
                rgb,
                width,
                alpha,
                dashed,
                ..
            } => {
                let px: Vec<(f64, f64)> = points.iter().map(|&p| plot.to_px(area, p)).collect();
                cv.polyline(&px, *width, *rgb, *alpha, *dashed);
            }
            Mark::Cross { at } => cv.cross(plot.to_px(area, *at)),
            Mark::Event { at, rgb, .. } => {
                let p = plot.to_px(area, *at);
                cv.disc(p, EVENT_RADIUS + 2.0, [255, 255, 255]);
                cv.disc(p, EVENT_RADIUS, *rgb);
            }
            Mark::Label {
                at,
                text,
                place,
                rgb,
                ..
            } => {
                let p = plot.to_px(area, *at);
                let w = pen.width(text);
                let top_left = match place {
                    Place::Below => (p.0 - w / 2.0, p.1 + 4.0),
                    Place::Left => (p.0 - w - 6.0, p.1 - 0.6 * LABEL_PX),
                };
                pen.write(cv, text, top_left, *rgb);
            }
        }
    }
}

/// A key's swatch, 26 px wide, its left middle at `at`.
fn swatch(cv: &mut Canvas, key: &Key, at: (f64, f64)) {
    let (x, y) = at;
    match key.swatch {
        Swatch::Line => cv.polyline(&[(x, y), (x + 26.0, y)], 2.5, key.rgb, 1.0, false),
        Swatch::Dashed => cv.polyline(&[(x, y), (x + 26.0, y)], 2.0, key.rgb, 1.0, true),
        Swatch::Dot => {
            cv.disc((x + 13.0, y), EVENT_RADIUS + 2.0, [255, 255, 255]);
            cv.disc((x + 13.0, y), EVENT_RADIUS, key.rgb);
        }
        Swatch::Cross => cv.cross((x + 13.0, y)),
    }
}

/// The legend in two columns in `area`.
fn paint_legend(cv: &mut Canvas, pen: &Pen, legend: &[Key], area: Area) {
    let rows = legend.len().div_ceil(2);
    for (k, key) in legend.iter().enumerate() {
        let (col, row) = (k / rows.max(1), k % rows.max(1));
        let x = area.left + col as f64 * area.width / 2.0;
        let y = area.top + (row as f64 + 0.5) * ROW_PX;
        swatch(cv, key, (x, y));
        pen.write(
            cv,
            &key.text,
            (x + 34.0, y - 0.6 * LABEL_PX),
            [215, 215, 222],
        );
    }
}

/// The legend's height under a plot of `legend`, px.
fn legend_px(legend: &[Key]) -> f64 {
    legend.len().div_ceil(2) as f64 * ROW_PX + 10.0
}

/// What the diagram shows, for tests and captions.
pub struct Drawn {
    /// The image.
    pub image: Image,
    /// The eye's observation event.
    pub eye: Event,
    /// Each puck's emission event: where the cone meets its worldline.
    pub emissions: Vec<Event>,
    /// The chosen frame's line of simultaneity.
    pub simultaneity: Option<Simultaneity>,
    /// Where the data was drawn in the image, px (diagram point to pixel:
    /// [`Plot::to_px`] with this area).
    pub area: Area,
    /// The plot drawn.
    pub plot: Plot,
}

/// Draws the diagram of `scene` (its `billiard` run to at least `t`) for
/// observer `observer` at board time `t`, `width × height` px.
#[must_use]
pub fn draw(
    scene: &Scene,
    billiard: &Billiard,
    observer: usize,
    t: f64,
    width: u32,
    height: u32,
) -> Drawn {
    draw_with(
        scene,
        billiard,
        observer,
        t,
        (width, height),
        Options::default(),
    )
}

/// [`draw`] with [`Options`] (axis, frame): the plot with its labels, and
/// under it the legend when the image is at least 480 × 360 px.
#[must_use]
pub fn draw_with(
    scene: &Scene,
    billiard: &Billiard,
    observer: usize,
    t: f64,
    (width, height): (u32, u32),
    options: Options,
) -> Drawn {
    let (eye, _) = crate::frame::eye_of(scene, observer, t);
    let plot = super::plot_with(scene, billiard, eye.event, options);
    let mut cv = Canvas::new(width, height);
    let pen = Pen::new();
    let legend = width >= LEGEND_FROM.0 && height >= LEGEND_FROM.1;
    let below = if legend { legend_px(&plot.legend) } else { 0.0 };
    let outer = Area {
        left: 0.0,
        top: 0.0,
        width: f64::from(width),
        height: f64::from(height) - below,
    };
    let area = outer.inside_margins();
    paint_marks(&mut cv, &pen, &plot, area);
    if legend {
        let strip = Area {
            left: area.left,
            top: outer.height + 4.0,
            width: area.width,
            height: below,
        };
        paint_legend(&mut cv, &pen, &plot.legend, strip);
    }
    Drawn {
        image: cv.img,
        eye: plot.eye,
        emissions: plot.emissions.clone(),
        simultaneity: plot.simultaneity,
        area,
        plot,
    }
}
