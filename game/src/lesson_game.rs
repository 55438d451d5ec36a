//! The game's side of [`LessonGame`], the only way a lesson's world
//! (`lightcone_lesson::WorldCore`, and Python's `World` around it)
//! reaches the game: on the desktop and in the browser alike.

use lightcone_engine::physics::Billiard;
use lightcone_engine::scene::{Effects, Scene};
use lightcone_lesson::{LessonGame, Pictures};

use crate::model::{GameState, ViewMode};

/// A game on an empty 1 m table: the game a lesson's `setup` builds on
/// (its `world.start(scene)` restarts it on the lesson's scene; the game
/// shown is replaced only once setup has ended well), and what a headless
/// run shows of a lesson that failed before starting one.
pub fn empty_game() -> GameState {
    let scene = Scene::empty(glam::DVec2::new(1.0, 1.0), None)
        .unwrap_or_else(|_| unreachable!("a 1 m table is a valid scene"));
    GameState::new(scene)
}

impl LessonGame for GameState {
    fn scene(&self) -> &Scene {
        &self.scene
    }

    fn billiard(&self) -> &Billiard {
        self.physics()
    }

    fn billiard_mut(&mut self) -> &mut Billiard {
        self.physics_mut()
    }

    fn live_time(&self) -> f64 {
        self.live_time
    }

    fn paused(&self) -> bool {
        self.paused
    }

    fn set_paused(&mut self, paused: bool) {
        self.paused = paused;
    }

    fn time_scale(&self) -> f64 {
        self.time_scale
    }

    fn set_time_scale(&mut self, scale: f64) {
        self.time_scale = scale;
    }

    fn pictures(&self) -> Pictures {
        match self.view {
            ViewMode::Seen => Pictures::Seen,
            ViewMode::Truth => Pictures::Truth,
            ViewMode::Split => Pictures::Split,
        }
    }

    fn set_pictures(&mut self, pictures: Pictures) {
        self.set_view(match pictures {
            Pictures::Seen => ViewMode::Seen,
            Pictures::Truth => ViewMode::Truth,
            Pictures::Split => ViewMode::Split,
        });
    }

    fn observer(&self) -> Option<usize> {
        self.observer
    }

    fn set_observer(&mut self, observer: Option<usize>) {
        self.observer = observer;
    }

    fn effects(&self) -> Effects {
        self.effects
    }

    fn effects_mut(&mut self) -> &mut Effects {
        &mut self.effects
    }

    fn set_diagram(
        &mut self,
        on: bool,
        frame: Option<usize>,
        axis: lightcone_render::diagram::Axis,
    ) {
        self.show.diagram = on;
        self.show.diagram_frame = frame;
        self.show.diagram_axis = axis;
    }

    fn restart(&mut self, scene: Scene) {
        *self = GameState::new(scene);
    }
}
