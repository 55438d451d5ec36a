//! What a lesson may read and change of the running game: the game
//! implements [`LessonGame`] on its state; this crate does not depend on
//! the game.

use lightcone_engine::physics::Billiard;
use lightcone_engine::scene::{Effects, Scene};

use crate::Pictures;

/// What a lesson may read and change of the running game. The game
/// implements it on its state; a world's call ([`crate::WorldCall`])
/// borrows it from the game's host for one request or one hook.
pub trait LessonGame {
    /// The scene being played.
    fn scene(&self) -> &Scene;
    /// The pucks and their worldlines.
    fn billiard(&self) -> &Billiard;
    /// The pucks, to strike one.
    fn billiard_mut(&mut self) -> &mut Billiard;
    /// Board time the physics has reached, s.
    fn live_time(&self) -> f64;
    /// Whether time stands still.
    fn paused(&self) -> bool;
    /// Stops or restarts time.
    fn set_paused(&mut self, paused: bool);
    /// Board seconds per real second.
    fn time_scale(&self) -> f64;
    /// Sets board seconds per real second (checked by the caller).
    fn set_time_scale(&mut self, scale: f64);
    /// Which pictures are shown.
    fn pictures(&self) -> Pictures;
    /// Chooses the pictures shown.
    fn set_pictures(&mut self, pictures: Pictures);
    /// Index of the scene observer whose eye is used (`None`: free eye).
    fn observer(&self) -> Option<usize>;
    /// Chooses the eye (an index into the scene's observers, checked by
    /// the caller).
    fn set_observer(&mut self, observer: Option<usize>);
    /// The effects shown.
    fn effects(&self) -> Effects;
    /// The effects shown, to turn one on or off.
    fn effects_mut(&mut self) -> &mut Effects;
    /// Opens or closes the live space-time diagram, with the puck whose
    /// lines of simultaneity it draws (`None`: only the board's) and the
    /// board axis across.
    fn set_diagram(
        &mut self,
        on: bool,
        frame: Option<usize>,
        axis: lightcone_render::diagram::Axis,
    );
    /// Starts the game again on `scene` at board time 0, as a new game
    /// on it would start (`world.start(scene)`; the world then restores
    /// what the student chose, see `WorldCall::start`).
    fn restart(&mut self, scene: Scene);
}
