//! Rest-frame meshes, built with parry: pucks (cylinders), the table's
//! cloth and cushions (cuboids), and a sphere for demonstrations. Board
//! coordinates: z up, the cloth's top face at z = 0.

use glam::DVec3;
use parry3d_f64::shape::{Ball, Cuboid, Cylinder};

use super::RestShape;

/// Vertices around each rim of a puck mesh.
pub const PUCK_SEGMENTS: u32 = 48;
/// Height of the cushions above the board, m.
pub const CUSHION_HEIGHT: f64 = 0.04;
/// Width of the cushions, m.
pub const CUSHION_WIDTH: f64 = 0.06;

/// Turns parry's y-up geometry into ours (z up): a rotation by +90° about x,
/// `(x, y, z) → (x, −z, y)`, which keeps the triangles' winding.
fn z_up(v: DVec3) -> DVec3 {
    DVec3::new(v.x, -v.z, v.y)
}

fn shape(vertices: Vec<DVec3>, triangles: Vec<[u32; 3]>, shift: DVec3, rotate: bool) -> RestShape {
    RestShape {
        vertices: vertices
            .into_iter()
            .map(|v| if rotate { z_up(v) } else { v } + shift)
            .collect(),
        triangles,
    }
}

/// A puck: a cylinder of `radius` and `height` standing on the board (its
/// reference point, the centre of its base, at the origin), `segments`
/// around.
#[must_use]
pub fn puck(radius: f64, height: f64, segments: u32) -> RestShape {
    let (v, t) = Cylinder::new(height / 2.0, radius).to_trimesh(segments.max(3));
    shape(v, t, DVec3::new(0.0, 0.0, height / 2.0), true)
}

/// A sphere of `radius` centred on its reference point.
#[must_use]
pub fn sphere(radius: f64, subdivisions: u32) -> RestShape {
    let s = subdivisions.max(3);
    let (v, t) = Ball::new(radius).to_trimesh(2 * s, s);
    shape(v, t, DVec3::ZERO, true)
}

/// A box with the given centre and half-extents (board axes).
#[must_use]
pub fn cuboid(centre: DVec3, half_extents: DVec3) -> RestShape {
    let (v, t) = Cuboid::new(half_extents).to_trimesh();
    shape(v, t, centre, false)
}

/// The table at rest on the board: the cloth (top face at z = 0) and four
/// cushions around the playing area `size`, `cushion_height` tall and
/// `cushion_width` wide, outside the area.
#[must_use]
pub fn table(size: glam::DVec2, cushion_height: f64, cushion_width: f64) -> Vec<RestShape> {
    let (w, h) = (cushion_width, cushion_height);
    let cloth_depth = 0.02;
    vec![
        cuboid(
            DVec3::new(size.x / 2.0, size.y / 2.0, -cloth_depth / 2.0),
            DVec3::new(size.x / 2.0 + w, size.y / 2.0 + w, cloth_depth / 2.0),
        ),
        cuboid(
            DVec3::new(-w / 2.0, size.y / 2.0, h / 2.0),
            DVec3::new(w / 2.0, size.y / 2.0 + w, h / 2.0),
        ),
        cuboid(
            DVec3::new(size.x + w / 2.0, size.y / 2.0, h / 2.0),
            DVec3::new(w / 2.0, size.y / 2.0 + w, h / 2.0),
        ),
        cuboid(
            DVec3::new(size.x / 2.0, -w / 2.0, h / 2.0),
            DVec3::new(size.x / 2.0, w / 2.0, h / 2.0),
        ),
        cuboid(
            DVec3::new(size.x / 2.0, size.y + w / 2.0, h / 2.0),
            DVec3::new(size.x / 2.0, w / 2.0, h / 2.0),
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn puck_stands_on_the_board_with_its_radius() {
        let p = puck(0.03, 0.02, 48);
        let zmin = p.vertices.iter().map(|v| v.z).fold(f64::INFINITY, f64::min);
        let zmax = p
            .vertices
            .iter()
            .map(|v| v.z)
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(zmin.abs() < 1e-15 && (zmax - 0.02).abs() < 1e-15);
        let rmax = p
            .vertices
            .iter()
            .map(|v| v.truncate().length())
            .fold(0.0, f64::max);
        assert!((rmax - 0.03).abs() < 1e-15);
        assert!(p.vertices.len() >= 96);
        // Outward winding: every triangle's normal points away from the axis
        // or along ±z at the caps.
        for t in &p.triangles {
            let [a, b, c] = t.map(|i| p.vertices[i as usize]);
            let n = (b - a).cross(c - a);
            let centroid = (a + b + c) / 3.0 - DVec3::new(0.0, 0.0, 0.01);
            assert!(n.dot(centroid) > 0.0, "{t:?}");
        }
    }

    #[test]
    fn table_cushions_surround_the_area() {
        let parts = table(glam::DVec2::new(2.84, 1.42), 0.04, 0.05);
        assert_eq!(parts.len(), 5);
        let all: Vec<DVec3> = parts.iter().flat_map(|p| p.vertices.clone()).collect();
        let xmax = all.iter().map(|v| v.x).fold(f64::NEG_INFINITY, f64::max);
        assert!((xmax - 2.89).abs() < 1e-12);
        let s = sphere(0.1, 8);
        assert!(s.vertices.iter().all(|v| (v.length() - 0.1).abs() < 1e-12));
    }
}
