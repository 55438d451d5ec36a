//! A fixed-step overlap detector: the usual game-engine way (move every
//! puck by `v dt`, then look for overlaps), kept only as the baseline that
//! shows what exact event anticipation buys. Not used by the game.
//!
//! Overlap of two contracted pucks is tested on the board at each step by
//! sampling each ellipse's rim against the other; a detected contact is
//! resolved at once with the same outcomes as the exact engine
//! ([`super::resolve`]), the normal taken along the line of centres.

use glam::{DVec2, DVec3};

use super::PuckInit;
use super::predict::Cushion;
use super::predict::puck_cushion::half_width;
use super::resolve::{self, Body};
use crate::spacetime::ProperVelocity;
use crate::worldline::contract;

/// Rim points sampled per puck in the overlap test.
const RIM_SAMPLES: usize = 32;

/// A contact the stepper detected.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Detected {
    /// Board time of the step that found it, s.
    pub t: f64,
    /// The pucks (`b` is `None` for a cushion).
    pub a: usize,
    /// Second puck, if any.
    pub b: Option<usize>,
    /// Centre of `a` then, m.
    pub position_a: DVec3,
}

/// The stepper's state.
pub struct FixedStep {
    c: f64,
    table: DVec2,
    position: Vec<DVec3>,
    u: Vec<ProperVelocity>,
    radius: Vec<f64>,
    mass: Vec<f64>,
    t: f64,
}

impl FixedStep {
    /// Pucks at board time 0.
    #[must_use]
    pub fn new(c: f64, table: DVec2, pucks: &[PuckInit]) -> Self {
        Self {
            c,
            table,
            position: pucks.iter().map(|p| p.position.extend(0.0)).collect(),
            u: pucks.iter().map(|p| p.u).collect(),
            radius: pucks.iter().map(|p| p.radius).collect(),
            mass: pucks.iter().map(|p| p.mass).collect(),
            t: 0.0,
        }
    }

    /// Board time, s.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.t
    }

    /// Centre of puck `i`, m.
    #[must_use]
    pub fn position(&self, i: usize) -> DVec3 {
        self.position[i]
    }

    /// One step of `dt` seconds; returns the contacts found and resolved.
    pub fn step(&mut self, dt: f64, found: &mut Vec<Detected>) {
        self.t += dt;
        for (p, u) in self.position.iter_mut().zip(&self.u) {
            *p += u.velocity(self.c) * dt;
        }
        let n = self.position.len();
        for i in 0..n {
            for cushion in Cushion::ALL {
                let k = cushion.axis();
                let s = cushion.outward_sign();
                let reach = s * (self.position[i][k] - cushion.line(self.table))
                    + half_width(self.radius[i], self.u[i], k);
                if reach >= 0.0 && self.u[i].0[k] * s > 0.0 {
                    self.u[i] = resolve::puck_cushion(self.u[i], cushion.outward(), 1.0);
                    found.push(Detected {
                        t: self.t,
                        a: i,
                        b: None,
                        position_a: self.position[i],
                    });
                }
            }
        }
        for i in 0..n {
            for j in i + 1..n {
                let d = self.position[j] - self.position[i];
                let closing =
                    (self.u[j].velocity(self.c) - self.u[i].velocity(self.c)).dot(d) < 0.0;
                if closing && self.overlap(i, j) {
                    let normal = d.normalize();
                    let frame = ProperVelocity(
                        (self.u[i].0 + self.u[j].0)
                            / (2.0
                                + 2.0
                                    * crate::spacetime::Boost::into_frame(self.u[i])
                                        .apply_velocity(self.u[j])
                                        .gamma())
                            .sqrt(),
                    );
                    let n_pair = crate::spacetime::Boost::into_frame(frame)
                        .apply(crate::spacetime::FourVector::new(0.0, normal))
                        .space
                        .normalize();
                    let [a, b] = resolve::puck_puck(
                        Body {
                            mass: self.mass[i],
                            u: self.u[i],
                        },
                        Body {
                            mass: self.mass[j],
                            u: self.u[j],
                        },
                        n_pair,
                        frame,
                        1.0,
                    );
                    self.u[i] = a.u;
                    self.u[j] = b.u;
                    found.push(Detected {
                        t: self.t,
                        a: i,
                        b: Some(j),
                        position_a: self.position[i],
                    });
                }
            }
        }
    }

    /// Whether the contracted pucks `i` and `j` overlap now (rim sampling).
    fn overlap(&self, i: usize, j: usize) -> bool {
        let (ri, rj) = (self.radius[i], self.radius[j]);
        let d = self.position[j] - self.position[i];
        if d.length() > ri + rj {
            return false;
        }
        self.rim_inside(i, j) || self.rim_inside(j, i)
    }

    /// Whether a sampled rim point of `i` lies inside `j`.
    fn rim_inside(&self, i: usize, j: usize) -> bool {
        let (uj, gj) = (self.u[j], self.u[j].gamma());
        let nj = if uj.0.length() > 0.0 {
            uj.0.normalize()
        } else {
            DVec3::X
        };
        (0..RIM_SAMPLES).any(|k| {
            let a = std::f64::consts::TAU * k as f64 / RIM_SAMPLES as f64;
            let rim = contract(
                DVec3::new(a.cos(), a.sin(), 0.0) * self.radius[i],
                self.u[i],
            );
            let rel = self.position[i] + rim - self.position[j];
            // Undo j's contraction: stretch the component along its motion.
            let along = rel.dot(nj);
            let rest = rel + nj * (along * (gj - 1.0));
            rest.length() < self.radius[j]
        })
    }
}
