//! What a lesson has put on the student's screen: its text, the question
//! it asked, the claims it checked, its bar charts and its closing
//! message. The window's lesson panel draws a [`LessonUi`]; the world's
//! operations (`crate::WorldCore`) change it.

use lightcone_engine::spacetime::Event;

/// Which pictures the game shows: what is seen, the truth, or both side by
/// side.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pictures {
    /// What the observer sees.
    Seen,
    /// The board as it is at the same board time.
    Truth,
    /// Both, side by side.
    Split,
}

impl Pictures {
    /// The name a lesson uses (`world.view`): "seen", "truth" or "split".
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Seen => "seen",
            Self::Truth => "truth",
            Self::Split => "split",
        }
    }

    /// The pictures named `name` (see [`Self::name`]), if any.
    #[must_use]
    pub fn named(name: &str) -> Option<Self> {
        [Self::Seen, Self::Truth, Self::Split]
            .into_iter()
            .find(|p| p.name() == name)
    }
}

/// A question on screen, waiting for (or answered with) a choice.
#[derive(Clone, Debug, PartialEq)]
pub struct Question {
    /// The question.
    pub text: String,
    /// The possible answers, shown as buttons.
    pub choices: Vec<String>,
    /// Index of the right answer, if the lesson gave one.
    pub answer: Option<usize>,
    /// Index the student chose, once they have.
    pub chosen: Option<usize>,
    /// The game was running when the question paused it (so answering
    /// resumes it).
    pub resume: bool,
}

impl Question {
    /// The choice a run with nobody to answer takes: the lesson's right
    /// answer, or the first choice when it names none.
    #[must_use]
    pub fn lessons_own(&self) -> usize {
        self.answer.unwrap_or(0)
    }
}

/// A physics claim the lesson checked, shown as ✓ or ✗ (and failing the
/// headless run when false).
#[derive(Clone, Debug, PartialEq)]
pub struct Claim {
    /// What is claimed.
    pub claim: String,
    /// Whether it held.
    pub ok: bool,
    /// The numbers behind it.
    pub detail: String,
}

/// Most claims a lesson may check (the shipped lessons check a few
/// dozen): past it `check` raises, so a flood of claims cannot grow the
/// game's memory or its panel.
pub const MAX_CLAIMS: usize = 10_000;

/// Longest claim, or claim's detail, in bytes of UTF-8.
pub const MAX_CLAIM_BYTES: usize = 4096;

/// Longest text of the lesson's message (`say`, appended lines and all)
/// or closing message, in bytes of UTF-8: a panel holds pages, not
/// megabytes (a 15 MB message stopped the browser's game).
pub const MAX_TEXT_BYTES: usize = 64 << 10;

/// Most choices a question may offer.
pub const MAX_CHOICES: usize = 16;

/// Most bar charts (by title) a lesson may show at once, and most bins a
/// chart may have.
pub const MAX_CHARTS: usize = 64;
/// See [`MAX_CHARTS`].
pub const MAX_BINS: usize = 10_000;

/// A bar chart (for instance a speed histogram) with an optional expected
/// curve drawn over it.
#[derive(Clone, Debug, PartialEq)]
pub struct Bars {
    /// Title above the chart.
    pub title: String,
    /// Bin edges (one more than the counts).
    pub edges: Vec<f64>,
    /// Bar heights.
    pub counts: Vec<f64>,
    /// Expected heights per bin, drawn as a line.
    pub expected: Option<Vec<f64>>,
}

/// Everything the lesson has put on screen.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LessonUi {
    /// The lesson's current text.
    pub text: String,
    /// The current question.
    pub question: Option<Question>,
    /// Claims checked so far, in order.
    pub claims: Vec<Claim>,
    /// Charts, by title (a chart with the same title replaces the old).
    pub bars: Vec<Bars>,
    /// Set by `finish`: the closing message (no hook runs after it).
    pub finished: Option<String>,
    /// Set by `finish(after_light_from=…)`: the board event (board time s,
    /// position m on the cloth, z = 0) whose light the closing message
    /// waits for. The game clears it once that light has reached the eye
    /// looked through; until then the message is not shown.
    pub finish_light: Option<Event>,
    /// The newest lines the lesson printed.
    pub printed: Vec<String>,
}

impl LessonUi {
    /// The closing message as the screen shows it: set by `finish`, and,
    /// when it waits for an event's light, once that light has arrived.
    #[must_use]
    pub fn closing(&self) -> Option<&str> {
        self.finished
            .as_deref()
            .filter(|_| self.finish_light.is_none())
    }

    /// The question waiting for the student's choice, if any.
    #[must_use]
    pub fn open_question(&self) -> Option<&Question> {
        self.question.as_ref().filter(|q| q.chosen.is_none())
    }

    /// The student chose `choice` for the open question: recorded.
    /// Returns the question's text, the choice's, and whether answering
    /// resumes time; `None` (nothing recorded) with no open question or a
    /// choice it does not offer.
    pub fn choose(&mut self, choice: usize) -> Option<(String, String, bool)> {
        let q = self.question.as_mut()?;
        if q.chosen.is_some() || choice >= q.choices.len() {
            return None;
        }
        q.chosen = Some(choice);
        Some((q.text.clone(), q.choices[choice].clone(), q.resume))
    }

    /// Lets the closing message show once the light of the event it waits
    /// for has reached `eye` (light at `c` m/s); whether it shows now (or
    /// never waited).
    pub fn light_arrived(&mut self, eye: Event, c: f64) -> bool {
        if self
            .finish_light
            .is_some_and(|sent| sent.light_has_reached(eye, c))
        {
            self.finish_light = None;
        }
        self.finish_light.is_none()
    }
}
