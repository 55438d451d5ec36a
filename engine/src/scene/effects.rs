//! The relativistic effects a view shows (`[effects]`): the names and the
//! flags.

use serde::{Deserialize, Serialize};

/// A relativistic effect a view can show. Physics (collisions, contraction
/// of the colliding shapes) is always relativistic; these select what the
/// *views* show, and each is implemented by systems that run only when it
/// is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Effect {
    /// Bodies drawn contracted along their motion (§3.2.2).
    Contraction,
    /// Bodies seen where they were when the light left them (§3.2.1).
    LightDelay,
    /// Directions transformed into the moving observer's frame.
    Aberration,
    /// Colours shifted by the Doppler factor.
    Doppler,
    /// Brightness scaled by the Doppler factor (searchlight / beaming).
    Searchlight,
    /// Clocks on bodies show proper time.
    TimeDilation,
}

impl Effect {
    /// Every effect, in the order of the `[effects]` table.
    pub const ALL: [Effect; 6] = [
        Effect::Contraction,
        Effect::LightDelay,
        Effect::Aberration,
        Effect::Doppler,
        Effect::Searchlight,
        Effect::TimeDilation,
    ];

    /// The key in the scene file.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Effect::Contraction => "contraction",
            Effect::LightDelay => "light_delay",
            Effect::Aberration => "aberration",
            Effect::Doppler => "doppler",
            Effect::Searchlight => "searchlight",
            Effect::TimeDilation => "time_dilation",
        }
    }
}

/// The `[effects]` flags: a scene's effect set (in the ECS each view
/// carries it as one marker component per effect, see `crate::ecs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Effects {
    /// See [`Effect::Contraction`]. Default on.
    pub contraction: bool,
    /// See [`Effect::LightDelay`]. Default on.
    pub light_delay: bool,
    /// See [`Effect::Aberration`]. Default on.
    pub aberration: bool,
    /// See [`Effect::Doppler`]. Default off.
    pub doppler: bool,
    /// See [`Effect::Searchlight`]. Default off.
    pub searchlight: bool,
    /// See [`Effect::TimeDilation`]. Default on.
    pub time_dilation: bool,
}

impl Default for Effects {
    fn default() -> Self {
        Self {
            contraction: true,
            light_delay: true,
            aberration: true,
            doppler: false,
            searchlight: false,
            time_dilation: true,
        }
    }
}

impl Effects {
    /// Every effect off: the Newtonian picture (for comparison views).
    pub const NONE: Self = Self {
        contraction: false,
        light_delay: false,
        aberration: false,
        doppler: false,
        searchlight: false,
        time_dilation: false,
    };

    /// Whether `effect` is on.
    #[must_use]
    pub fn is_on(&self, effect: Effect) -> bool {
        *self.flag(effect)
    }

    /// Turns `effect` on or off.
    pub fn set(&mut self, effect: Effect, on: bool) {
        *self.flag_mut(effect) = on;
    }

    fn flag(&self, effect: Effect) -> &bool {
        match effect {
            Effect::Contraction => &self.contraction,
            Effect::LightDelay => &self.light_delay,
            Effect::Aberration => &self.aberration,
            Effect::Doppler => &self.doppler,
            Effect::Searchlight => &self.searchlight,
            Effect::TimeDilation => &self.time_dilation,
        }
    }

    fn flag_mut(&mut self, effect: Effect) -> &mut bool {
        match effect {
            Effect::Contraction => &mut self.contraction,
            Effect::LightDelay => &mut self.light_delay,
            Effect::Aberration => &mut self.aberration,
            Effect::Doppler => &mut self.doppler,
            Effect::Searchlight => &mut self.searchlight,
            Effect::TimeDilation => &mut self.time_dilation,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn effects_flags_round_trip() {
        let mut e = Effects::NONE;
        for effect in Effect::ALL {
            assert!(!e.is_on(effect));
            e.set(effect, true);
            assert!(e.is_on(effect));
        }
    }
}
