//! Why a run ended, as a record: a kind spelled as the written files spell it, and the details
//! in words.
//!
//! The simulation's [`StopReason`] carries numbers; a front end needs a word to write and to
//! match on, and a sentence to show. Both come from here, so no front end spells a stop reason
//! of its own or matches on a string.

use std::f64::consts::FRAC_PI_2;

use model_runtime::Readable;

use crate::config::AllowedModes;
use crate::hybrid::{RunOutcome, StopReason};
use crate::modes::Mode;

/// Why a run ended, as a word (its serde name is what `events.csv`, `summary.json` and
/// `sweep.csv` write).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StopKind {
    /// The configured end time was reached.
    EndTime,
    /// `N` fell through zero.
    ContactLost,
    /// θ reached the configured floor above 0 (the disk lies flat).
    #[serde(rename = "inclination_reached_0")]
    InclinationReached0,
    /// θ reached the floor below π (the disk fell over past upright, onto its other face).
    #[serde(rename = "inclination_reached_pi")]
    InclinationReachedPi,
    /// Too many transitions within the chattering window.
    Chattering,
    /// Stopped on request (Ctrl-C, a closed output, a time budget).
    Interrupted,
    /// The disk entered a mode the scene does not allow.
    ModeNotAllowed,
    /// The simulation failed.
    Error,
}

impl StopKind {
    /// Every kind, in the order above.
    pub const ALL: [StopKind; 8] = [
        StopKind::EndTime,
        StopKind::ContactLost,
        StopKind::InclinationReached0,
        StopKind::InclinationReachedPi,
        StopKind::Chattering,
        StopKind::Interrupted,
        StopKind::ModeNotAllowed,
        StopKind::Error,
    ];

    /// The kind's name in written files (its serde name).
    pub fn name(self) -> &'static str {
        match self {
            StopKind::EndTime => "end_time",
            StopKind::ContactLost => "contact_lost",
            StopKind::InclinationReached0 => "inclination_reached_0",
            StopKind::InclinationReachedPi => "inclination_reached_pi",
            StopKind::Chattering => "chattering",
            StopKind::Interrupted => "interrupted",
            StopKind::ModeNotAllowed => "mode_not_allowed",
            StopKind::Error => "error",
        }
    }

    /// Whether the run failed (an error, or a mode the scene forbids) rather than ending by
    /// itself or on request.
    pub fn is_failure(self) -> bool {
        matches!(self, StopKind::Error | StopKind::ModeNotAllowed)
    }
}

impl std::fmt::Display for StopKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl StopReason {
    /// The reason's kind.
    pub fn kind(&self) -> StopKind {
        match self {
            StopReason::EndTime => StopKind::EndTime,
            StopReason::ContactLost { .. } => StopKind::ContactLost,
            StopReason::InclinationReachedFloor { theta, .. } if *theta > FRAC_PI_2 => {
                StopKind::InclinationReachedPi
            }
            StopReason::InclinationReachedFloor { .. } => StopKind::InclinationReached0,
            StopReason::Chattering { .. } => StopKind::Chattering,
            StopReason::Requested { .. } => StopKind::Interrupted,
            StopReason::ModeNotAllowed { .. } => StopKind::ModeNotAllowed,
        }
    }

    /// The reason's numbers in words (empty at the end time); `allowed` are the modes the run
    /// was allowed.
    pub fn detail(&self, allowed: AllowedModes) -> String {
        match *self {
            StopReason::EndTime => String::new(),
            StopReason::ModeNotAllowed { t, mode } => format!(
                "the disk entered {mode} at t = {} s but modes.allowed = {:?}",
                Readable(t),
                allowed.modes().iter().map(|m| m.name()).collect::<Vec<_>>()
            ),
            StopReason::Requested { t } => format!("stopped on request at t = {} s", Readable(t)),
            StopReason::ContactLost { t, mode } => {
                format!("N fell through 0 at t = {} s while {mode}", Readable(t))
            }
            StopReason::InclinationReachedFloor { t, theta } => {
                format!("theta = {} rad at t = {} s", Readable(theta), Readable(t))
            }
            StopReason::Chattering {
                t,
                transitions,
                window,
            } => format!(
                "{transitions} transitions within {} s at t = {} s",
                Readable(window),
                Readable(t)
            ),
        }
    }
}

/// Why a run ended, where and in which mode.
#[derive(Clone, Debug, PartialEq)]
pub struct Stop {
    /// Time (s).
    pub t: f64,
    /// The mode in force (for a mode not allowed: the mode the disk entered).
    pub mode: Mode,
    /// Why, as a word.
    pub kind: StopKind,
    /// Details (numbers, the error's message), may be empty.
    pub detail: String,
}

impl Stop {
    /// The stop of a run that ended with `outcome`; `allowed` are the modes it was allowed.
    pub fn of(outcome: &RunOutcome, allowed: AllowedModes) -> Stop {
        let mode = match outcome.stop {
            StopReason::ModeNotAllowed { mode, .. } => mode,
            _ => outcome.last.mode,
        };
        Stop {
            t: outcome.last.t,
            mode,
            kind: outcome.stop.kind(),
            detail: outcome.stop.detail(allowed),
        }
    }

    /// The stop of a run that failed at `t` in `mode` with `message`.
    pub fn failed(t: f64, mode: Mode, message: String) -> Stop {
        Stop {
            t,
            mode,
            kind: StopKind::Error,
            detail: message,
        }
    }

    /// This stop, if it was a request, as the user's interrupt (Ctrl-C); any other stop
    /// unchanged.
    pub fn by_the_user(self) -> Stop {
        if self.kind != StopKind::Interrupted {
            return self;
        }
        Stop {
            detail: format!("stopped by the user (Ctrl-C) at t = {} s", self.t),
            ..self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_the_serde_names_and_unique() {
        use serde::de::value::{Error, StrDeserializer};
        use serde::de::IntoDeserializer;
        let mut names: Vec<_> = StopKind::ALL.iter().map(|k| k.name()).collect();
        for kind in StopKind::ALL {
            let de: StrDeserializer<'_, Error> = kind.name().into_deserializer();
            let back: StopKind = serde::Deserialize::deserialize(de).unwrap();
            assert_eq!(back, kind);
        }
        names.sort();
        names.dedup();
        assert_eq!(names.len(), StopKind::ALL.len());
    }

    #[test]
    fn the_inclination_names_the_face_the_disk_lies_on() {
        let floor = 1e-9;
        let flat = StopReason::InclinationReachedFloor {
            t: 1.0,
            theta: floor,
        };
        let over = StopReason::InclinationReachedFloor {
            t: 1.0,
            theta: std::f64::consts::PI - floor,
        };
        assert_eq!(flat.kind(), StopKind::InclinationReached0);
        assert_eq!(over.kind(), StopKind::InclinationReachedPi);
        // The word and the library's own name agree.
        for r in [flat, over] {
            assert_eq!(r.kind().name().replace('_', " "), r.name());
        }
    }

    #[test]
    fn only_a_request_becomes_the_users_interrupt() {
        let stop = |kind| Stop {
            t: 2.5,
            mode: Mode::Rolling,
            kind,
            detail: "d".into(),
        };
        let by_user = stop(StopKind::Interrupted).by_the_user();
        assert_eq!(by_user.detail, "stopped by the user (Ctrl-C) at t = 2.5 s");
        assert_eq!(
            stop(StopKind::EndTime).by_the_user(),
            stop(StopKind::EndTime)
        );
        assert!(StopKind::Error.is_failure() && !StopKind::ContactLost.is_failure());
    }
}
