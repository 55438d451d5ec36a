//! Whether pucks overlap at t = 0, and the O(N) search for every puck that
//! overlaps an earlier one (the scene rule "pucks apart").

use super::model::PuckSpec;

/// Whether the rest-frame discs of `a` and `b` overlap at t = 0 (touching,
/// to a relative 10⁻¹², is allowed: pucks placed in contact to the digits of
/// the file are not called overlapping).
#[must_use]
pub fn overlap(a: &PuckSpec, b: &PuckSpec) -> bool {
    let reach = a.radius + b.radius;
    a.position.distance(b.position) < reach * (1.0 - 1e-12)
}

/// For each puck `j` whose rest-frame disc overlaps that of an earlier puck
/// at t = 0, one pair `(i, j)` with `i < j` (the first such `i` the search
/// meets; touching is allowed), in increasing `j`. At most one pair per
/// puck, so 10⁵ pucks at one point give 10⁵ − 1 pairs, not 5·10⁹.
///
/// A uniform grid of cells twice the median radius: each puck is filed
/// under the cells its bounding square covers and compared only with the
/// pucks filed there, so the cost is O(N) for pucks of similar size
/// however they are laid out (on a line, in a crowd, all at one point). A
/// puck covering more than 16 cells (much larger than the median) is kept
/// on a short list compared with every puck.
///
/// The rest-frame disc is conservative: a contracted puck lies inside it.
pub fn first_overlaps(pucks: &[PuckSpec]) -> Vec<(usize, usize)> {
    use std::collections::HashMap;
    if pucks.len() < 2 {
        return Vec::new();
    }
    let mut radii: Vec<f64> = pucks.iter().map(|p| p.radius).collect();
    let mid = radii.len() / 2;
    let (_, median, _) = radii.select_nth_unstable_by(mid, f64::total_cmp);
    let cell = 2.0 * *median;
    let index = |x: f64| (x / cell).floor() as i64;
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    let mut big: Vec<usize> = Vec::new();
    let mut pairs = Vec::new();
    for (j, p) in pucks.iter().enumerate() {
        let (x0, x1) = (
            index(p.position.x - p.radius),
            index(p.position.x + p.radius),
        );
        let (y0, y1) = (
            index(p.position.y - p.radius),
            index(p.position.y + p.radius),
        );
        let cells = (x1 - x0 + 1).saturating_mul(y1 - y0 + 1);
        let found = if cells > 16 {
            (0..j).find(|&i| overlap(&pucks[i], p))
        } else {
            let mut found = big.iter().copied().find(|&i| overlap(&pucks[i], p));
            'cells: for cx in x0..=x1 {
                for cy in y0..=y1 {
                    if found.is_some() {
                        break 'cells;
                    }
                    if let Some(list) = grid.get(&(cx, cy)) {
                        found = list.iter().copied().find(|&i| overlap(&pucks[i], p));
                    }
                }
            }
            found
        };
        if let Some(i) = found {
            pairs.push((i, j));
        }
        if cells > 16 {
            big.push(j);
        } else {
            for cx in x0..=x1 {
                for cy in y0..=y1 {
                    grid.entry((cx, cy)).or_default().push(j);
                }
            }
        }
    }
    pairs
}
