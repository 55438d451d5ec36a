//! Where each puck's name and clock are written so that no two labels
//! overlap: pucks by priority (the aimed one, the followed one, then the
//! fastest), each label tried in a few places round its ring (name above
//! and clock below, then both to the right, to the left), the clock dropped
//! before the name, and a label with no free place left out. A label does
//! not cover another puck's ring either (except the first puck's, when it
//! has no other place). A heap of pucks (a gas) keeps the labels of the
//! ones that matter readable.

use egui::{Pos2, Rect, Vec2};

/// Where a puck is marked: its ring's centre and radius, logical px.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Anchor {
    /// The ring's centre, logical px.
    pub centre: Pos2,
    /// The ring's radius, logical px.
    pub ring: f32,
}

/// One text to write: where (its box, logical px) and what.
#[derive(Clone, Debug, PartialEq)]
pub struct Placed {
    /// The marker it belongs to (index into the markers given).
    pub marker: usize,
    /// The text's box, logical px.
    pub rect: Rect,
    /// The name (`false`: the clock).
    pub is_name: bool,
}

/// Gap between a ring and its text, and between texts, logical px.
const GAP: f32 = 1.0;

/// Places the labels of the pucks marked at `markers`. `size(i,
/// is_name)`: the size of marker `i`'s name or clock text, logical px.
/// `priority[i]`: larger first. No label goes over a box of `blocked`
/// (an inset). Returns boxes of which no two intersect.
pub fn place(
    markers: &[Anchor],
    priority: &[f64],
    blocked: &[Rect],
    size: impl Fn(usize, bool) -> Vec2,
) -> Vec<Placed> {
    let mut order: Vec<usize> = (0..markers.len()).collect();
    order.sort_by(|&a, &b| {
        let (pa, pb) = (
            priority.get(a).copied().unwrap_or(0.0),
            priority.get(b).copied().unwrap_or(0.0),
        );
        pb.total_cmp(&pa).then(a.cmp(&b))
    });
    let rings: Vec<Rect> = markers
        .iter()
        .map(|m| Rect::from_center_size(m.centre, Vec2::splat(2.0 * m.ring)))
        .collect();
    let mut taken: Vec<Rect> = blocked.to_vec();
    let mut out = Vec::new();
    for (rank, i) in order.into_iter().enumerate() {
        let m = &markers[i];
        let c = m.centre;
        let r = m.ring + GAP;
        let (name, clock) = (size(i, true), size(i, false));
        let clear_of_rings = |rect: &Rect| {
            !rings
                .iter()
                .enumerate()
                .any(|(k, ring)| k != i && ring.intersect(*rect).is_positive())
        };
        let free = |rect: &Rect| !taken.iter().any(|t| t.intersects(*rect));
        // Candidate places: both texts, then the name alone.
        let above = Rect::from_min_size(c + Vec2::new(-name.x / 2.0, -r - name.y), name);
        let below = Rect::from_min_size(c + Vec2::new(-clock.x / 2.0, r), clock);
        let right_name = Rect::from_min_size(c + Vec2::new(r, -name.y), name);
        let right_clock = Rect::from_min_size(c + Vec2::new(r, 0.0), clock);
        let left_name = Rect::from_min_size(c + Vec2::new(-r - name.x, -name.y), name);
        let left_clock = Rect::from_min_size(c + Vec2::new(-r - clock.x, 0.0), clock);
        let pairs = [
            (above, Some(below)),
            (right_name, Some(right_clock)),
            (left_name, Some(left_clock)),
            (above, None),
            (right_name, None),
            (left_name, None),
            (
                Rect::from_min_size(c + Vec2::new(-name.x / 2.0, r), name),
                None,
            ),
        ];
        let fits = |(n, k): &(Rect, Option<Rect>), rings: bool| {
            free(n)
                && (!rings || clear_of_rings(n))
                && k.is_none_or(|k| free(&k) && (!rings || clear_of_rings(&k)))
        };
        let chosen = pairs
            .iter()
            .find(|p| fits(p, true))
            .or_else(|| pairs.iter().find(|p| rank == 0 && fits(p, false)))
            .copied();
        if let Some((n, k)) = chosen {
            taken.push(n.expand(GAP / 2.0));
            out.push(Placed {
                marker: i,
                rect: n,
                is_name: true,
            });
            if let Some(k) = k {
                taken.push(k.expand(GAP / 2.0));
                out.push(Placed {
                    marker: i,
                    rect: k,
                    is_name: false,
                });
            }
        }
    }
    out
}

/// Whether any two of `placed` intersect (what [`place`] never gives).
pub fn any_overlap(placed: &[Placed]) -> bool {
    placed.iter().enumerate().any(|(k, a)| {
        placed[k + 1..]
            .iter()
            .any(|b| a.rect.intersect(b.rect).is_positive())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    fn marker(x: f32, y: f32) -> Anchor {
        Anchor {
            centre: Pos2::new(x, y),
            ring: 16.0,
        }
    }

    fn size(_: usize, is_name: bool) -> Vec2 {
        if is_name {
            Vec2::new(40.0, 14.0)
        } else {
            Vec2::new(44.0, 13.0)
        }
    }

    #[test]
    fn lone_pucks_keep_name_above_and_clock_below() {
        let markers = [marker(100.0, 100.0), marker(400.0, 100.0)];
        let placed = place(&markers, &[0.0, 0.0], &[], size);
        assert_eq!(placed.len(), 4);
        let name = placed.iter().find(|p| p.marker == 0 && p.is_name).unwrap();
        let clock = placed.iter().find(|p| p.marker == 0 && !p.is_name).unwrap();
        assert!((name.rect.max.y - (100.0 - 17.0)).abs() < 1e-4);
        assert!((clock.rect.min.y - (100.0 + 17.0)).abs() < 1e-4);
        assert!((name.rect.center().x - 100.0).abs() < 1e-4);
    }

    #[test]
    fn a_heap_of_pucks_gets_labels_that_never_overlap_and_the_first_first() {
        // 120 pucks in a 300 × 200 px heap (the gas lesson's table seen
        // from afar): most labels cannot fit.
        let markers: Vec<Anchor> = (0..120u16)
            .map(|k| {
                marker(
                    100.0 + f32::from(k % 12) * 25.0,
                    100.0 + f32::from(k / 12) * 20.0,
                )
            })
            .collect();
        let mut priority = vec![0.0; 120];
        priority[57] = 10.0;
        let placed = place(&markers, &priority, &[], size);
        assert!(!any_overlap(&placed));
        assert!(placed.iter().filter(|p| p.is_name).count() < 120);
        // The most important puck keeps both its name and its clock.
        assert_eq!(placed[0].marker, 57);
        assert_eq!(placed.iter().filter(|p| p.marker == 57).count(), 2);
        // Overlap is what it says.
        let mut bad = placed.clone();
        bad.push(placed[0].clone());
        assert!(any_overlap(&bad));
    }
}
