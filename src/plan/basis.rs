//! What a `--tolerance` choice rests on: a pilot that held, the pilots' own model, a committed
//! model (the release atlas, the one law) or the linear theory of a small mode, in the words
//! the run's announcement and summary use.

/// Where a `--tolerance` choice's predicted error comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Basis {
    /// A pilot at the chosen method and N held EPS by its own estimate ([`Pilot::bound`](super::pilot::Pilot::bound)).
    Held,
    /// The scene's own error model, fitted to the pilots' estimates ([`Pilot::model`](super::pilot::Pilot::model)).
    OwnModel,
    /// The committed model, asking fewer segments than the pilots' own ([`ruling_model`](super::pilot::ruling_model)).
    CommittedTighter,
    /// The committed model, for a release, where the pilots' own asked fewer segments
    /// ([`Committed::floors_pilots`](super::committed::Committed::floors_pilots)).
    CommittedOverPilots,
    /// The committed model alone: no pilot was worth its cost, or none measured anything.
    Committed,
    /// The linear theory of the rods' small oscillations ([`mode_theory`](super::mode_theory)):
    /// their error at every instant of the run, worked out before it, times [`SAFETY`](super::error_model::SAFETY).
    Theory,
    /// The committed model, from the release atlas of the chosen rods
    /// ([`from_atlas`](super::committed::from_atlas)): their error measured at this angle, or from
    /// its neighbours, or the envelope of every angle's, up to large N, alone or tighter than the
    /// pilots' own.
    Atlas,
}

impl Basis {
    /// What the choice rests on, in a sentence's words (the run's announcement and its
    /// summary say it).
    pub fn meaning(self) -> &'static str {
        match self {
            Self::Held => "the scene's own error, measured by the pilot at this N",
            Self::OwnModel => "the scene's own error model, from the pilots",
            Self::CommittedTighter => {
                "the committed error model, here tighter than the pilots' own (measured at N ≤ 64)"
            }
            Self::CommittedOverPilots => {
                "the committed error model, measured up to large N, over the pilots' own, which asked fewer rods: a release's error constant goes on growing past the pilots' N ≤ 64"
            }
            Self::Atlas => {
                "the release atlas of the chosen rods: their worst error to t = 3 (to t = 5 from 40°) at every 1/3000 of a time unit, measured every 5° of release angle against converged references: at this angle, or from its two neighbours or every angle's largest, times the margin measured for each (`scripts/release-atlas.sh`; docs/guide.md, § --tolerance)"
            }
            Self::Theory => {
                "the linear theory of the rods' small oscillations: their tip against the string's mode at every 1/3000 of the run, worked out before it, times 1.5 (it bounds the chain's error within 0.93 to 1.19 for modes 1 and 2 up to a tip amplitude of 0.1, to t = 10: `cargo run --release --example mode_theory`)"
            }
            Self::Committed => {
                "the committed error model, fitted to t = 3 over six scenes by `rope study --estimate-check`, no cheaper run found by the pilots that were worth their cost"
            }
        }
    }

    /// A few words for a table.
    pub fn label(self) -> &'static str {
        match self {
            Self::Held => "a pilot held",
            Self::OwnModel => "pilots' model",
            Self::CommittedTighter | Self::CommittedOverPilots | Self::Committed => {
                "committed model"
            }
            Self::Atlas => "release atlas",
            Self::Theory => "linear theory",
        }
    }
}
