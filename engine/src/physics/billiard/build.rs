//! Building a billiard: its pucks in name order, their shells and first
//! predictions, and the switches (reference loop, friction, recording)
//! set before it runs.

use super::*;

impl Billiard {
    /// A billiard on a table of `table` metres with speed of light `c`,
    /// restitutions for puck–puck and puck–cushion collisions, and pucks at
    /// board time 0. The caller guarantees what scene validation checks
    /// (finite numbers, pucks on the table and apart).
    #[must_use]
    pub fn new(
        c: f64,
        table: DVec2,
        restitution: f64,
        cushion_restitution: f64,
        pucks: Vec<PuckInit>,
    ) -> Self {
        let mean_radius = if pucks.is_empty() {
            0.03
        } else {
            pucks.iter().map(|p| p.radius).sum::<f64>() / pucks.len() as f64
        };
        let n = pucks.len();
        let mut pucks: Vec<Puck> = pucks
            .into_iter()
            .enumerate()
            .map(|(k, p)| Puck {
                worldline: Worldline::new(Event::new(0.0, p.position.extend(0.0)), p.u, c),
                name: p.name,
                external: k as u32,
                radius: p.radius,
                mass: p.mass,
                version: 0,
                pending: SmallVec::new(),
                kicked_by: None,
                quick: (f64::NEG_INFINITY, 0),
            })
            .collect();
        // Canonical order: by name, then (for equal names) by the caller's
        // order. Every tie between simultaneous events is broken in it.
        pucks.sort_by(|a, b| a.name.cmp(&b.name).then(a.external.cmp(&b.external)));
        let mut internal = vec![0u32; n];
        for (i, p) in pucks.iter().enumerate() {
            internal[p.external as usize] = i as u32;
        }
        let mut billiard = Self {
            c,
            table,
            restitution,
            cushion_restitution,
            pucks,
            internal,
            time: 0.0,
            until: f64::INFINITY,
            calendar: Calendar::new(n),
            next: vec![
                Next {
                    what: What::Shell,
                    predicted_at: 0.0,
                };
                n
            ],
            hits: vec![None; n],
            kicks: Vec::new(),
            free_kicks: Vec::new(),
            contacts_made: 0,
            broad: BroadPhase::new(&[], &[]),
            shells: vec![DVec2::ZERO; n],
            hot: vec![Hot::default(); n],
            deceleration: 0.0,
            bounded: Vec::new(),
            margin: SHELL_MARGIN * mean_radius,
            reference: false,
            driven: false,
            collisions: Vec::new(),
            collisions_dropped: 0,
            record: true,
            history: None,
            forgotten_before: None,
            warnings: Vec::new(),
            zeno_said: false,
            stats: Stats::default(),
        };
        billiard.start();
        billiard
    }

    /// Every shell about its puck's centre and every puck predicted, at the
    /// current time.
    pub(super) fn start(&mut self) {
        // Of the worldlines and of their newest segments (one written from
        // elsewhere may brake harder than its worldline's own rule), as
        // `written` keeps it.
        self.deceleration = self
            .pucks
            .iter()
            .map(|p| {
                p.worldline
                    .deceleration()
                    .max(p.worldline.last().deceleration())
            })
            .fold(0.0, f64::max);
        for i in 0..self.pucks.len() {
            self.shells[i] = self.pucks[i]
                .worldline
                .last()
                .position_at(self.time)
                .truncate();
        }
        self.hot = self
            .pucks
            .iter()
            .map(|p| Hot::of(p, f64::INFINITY))
            .collect();
        let half: Vec<f64> = self.pucks.iter().map(|p| p.radius + self.margin).collect();
        self.broad = BroadPhase::new(&self.shells, &half);
        for i in 0..self.pucks.len() {
            self.hot[i].exit = self.shell_exit(i);
        }
        for i in 0..self.pucks.len() {
            self.predict(i);
        }
    }

    /// Switches to the slow reference path, kept for tests: every pair of
    /// pucks is a candidate (no broad phase), no cheap bound prunes any, and
    /// each pair contact is predicted again when it happens instead of kept.
    /// The physics is the same; a test checks that the fast loop gives the
    /// same contacts. Call before running.
    pub fn set_reference_loop(&mut self, on: bool) {
        self.reference = on;
        self.start();
    }

    /// Puts sliding friction on the table: every moving puck brakes with
    /// proper deceleration `deceleration` (`μ g`, m/s², board frame; 0 is
    /// frictionless), from its state at board time 0 (see
    /// `predict::braking`). Call before running; a non-finite or negative
    /// value is taken as 0.
    pub fn set_sliding_friction(&mut self, deceleration: f64) {
        for puck in &mut self.pucks {
            // A puck resting until struck at its start (`before_start =
            // "rest"`) has that rest segment first, at the same start: the
            // braking begins with the stroke, and the rest is kept.
            let segments = puck.worldline.segments();
            let rests_first = segments.len() > 1
                && segments[0].start.t == segments[1].start.t
                && segments[0].u == ProperVelocity::ZERO;
            let stroke = segments[usize::from(rests_first)];
            puck.worldline = Worldline::braking(stroke.start, stroke.u, self.c, deceleration);
            if rests_first {
                puck.worldline.rest_before_start();
            }
        }
        self.start();
    }

    /// The billiard of a validated scene.
    pub fn from_scene(scene: &Scene) -> Self {
        let pucks = scene.pucks.iter().map(PuckInit::from).collect();
        let mut billiard = Self::new(
            scene.c,
            scene.table.size,
            scene.restitution,
            scene.table.cushion_restitution,
            pucks,
        );
        if scene.table.deceleration() > 0.0 {
            billiard.set_sliding_friction(scene.table.deceleration());
        }
        // `before_start = "rest"`: each puck rests until struck at t = 0.
        if scene.before_start == crate::scene::BeforeStart::Rest {
            for puck in &mut billiard.pucks {
                puck.worldline.rest_before_start();
            }
        }
        billiard
    }

    /// Whether to keep a log of collisions (on by default; long benchmark
    /// runs turn it off).
    pub fn set_recording(&mut self, on: bool) {
        self.record = on;
    }
}
