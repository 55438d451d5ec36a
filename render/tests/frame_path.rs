//! The frame path (what the renderer draws, headless) and `observe` read
//! the same view of the frame schedule: the same apparent vertices to
//! 1e-12 (issue 12).

use glam::DVec3;
use lightcone_engine::ecs::BodyRef;
use lightcone_engine::scene;
use lightcone_render::frame::{self, ViewKind, ViewMeshes};
use lightcone_render::observe::report_at;

#[test]
fn the_frame_path_and_observe_see_the_same_vertices() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/scenes/paper_carom.toml"
    );
    let scene = scene::load(std::path::Path::new(path)).unwrap();
    for kind in [ViewKind::Seen, ViewKind::Truth] {
        for t in [0.5, 2.2, 4.0] {
            let (mut sim, view) = frame::scene_view(&scene, 0, t, kind, 16.0 / 9.0);
            let meshes = ViewMeshes::new(&mut sim);
            let apparent = sim.apparent(view).unwrap().clone();
            let corners = frame::view_corners(&apparent, &meshes);
            let report = report_at(&scene, 0, t, kind.effects(scene.effects), true).unwrap();
            // The frame's corners list the pucks first, each triangle's
            // three vertices in mesh order.
            let shapes: Vec<_> = sim
                .body_meshes()
                .into_iter()
                .filter_map(|(b, m, _)| match b {
                    BodyRef::Puck(i) => Some((i, m.shape.triangles.clone())),
                    BodyRef::Fixture(_) => None,
                })
                .collect();
            let mut k = 0;
            for (i, puck) in report.pucks.iter().enumerate() {
                let triangles = &shapes.iter().find(|(j, _)| *j == i).unwrap().1;
                let vertices = puck.vertices.as_ref().unwrap();
                for tri in triangles {
                    for &v in tri {
                        let p = &vertices[v as usize];
                        let expected = DVec3::from_array(p.direction) * p.distance;
                        let got = corners[k];
                        assert!(
                            (got.position - expected).length() <= 1e-12 * (1.0 + p.distance),
                            "{kind:?} t = {t}: {} vs {expected}",
                            got.position
                        );
                        assert!((got.doppler - p.doppler).abs() <= 1e-12 * p.doppler);
                        assert!((got.intensity - p.intensity).abs() <= 1e-12 * p.intensity);
                        k += 1;
                    }
                }
            }
            assert!(k > 0 && k < corners.len(), "the table follows the pucks");
        }
    }
}
