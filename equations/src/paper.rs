//! What the paper reports of its 100 s run, said once.
//!
//! The summary's comparison table, the figures' legends and the sound's rate figure all show
//! the paper's numbers beside ours; each reads them from here, so a correction to a reported
//! value (a misread digit of the OCR copy, say) is made in one line. docs/physics.md gives the
//! source of each (the paper's section 4 and its Figs. 8–10).

/// The time after which the paper reports the settled amplitudes (s).
pub const SETTLED_AFTER_S: f64 = 50.0;

/// The θ oscillation's angular frequency in the first second (s⁻¹; period 0.14 s). The knocks
/// of the sound follow it, so the sound's rate figure shows it too.
pub const THETA_OMEGA_FIRST: f64 = 44.0;

/// The θ oscillation's angular frequency in the last second of the 100 s run (s⁻¹).
pub const THETA_OMEGA_LAST: f64 = 149.0;

/// The knock rate the paper reads off a recording of the real toy (angular, s⁻¹).
pub const RECORDED_OMEGA: f64 = 154.0;

/// A value the paper reports for a key of the run's summary, as the paper prints it (some are
/// bounds or approximations: `"~0.05"`, `"> 0"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Reported {
    /// The summary key (docs/summary-keys.md).
    pub key: &'static str,
    /// The paper's value, as printed.
    pub value: &'static str,
}

/// Every summary key the paper gives a value for, in the summary's order.
pub const REPORTED: &[Reported] = &[
    Reported {
        key: "start_mode",
        value: "sliding",
    },
    Reported {
        key: "stop_reason",
        value: "end_time (contact kept)",
    },
    Reported {
        key: "t_end",
        value: "100",
    },
    Reported {
        key: "transitions",
        value: "over 6000 (an independent run)",
    },
    Reported {
        key: "theta_period_first_s",
        value: "0.14",
    },
    Reported {
        key: "theta_period_last_s",
        value: "0.042",
    },
    Reported {
        key: "theta_omega_first",
        value: "44",
    },
    Reported {
        key: "theta_omega_last",
        value: "149",
    },
    Reported {
        key: "theta_max_after_50s",
        value: "~0.05",
    },
    Reported {
        key: "slip_speed_max_after_50s",
        value: "~8e-4",
    },
    Reported {
        key: "nu_sliding",
        value: "0.115",
    },
    Reported {
        key: "nu_max",
        value: "0.2",
    },
    Reported {
        key: "rolling_phases_long_per_s_last",
        value: "~24",
    },
    Reported {
        key: "n_over_mg_min",
        value: "> 0",
    },
];

/// The paper's value for the summary key `key`, if it reports one.
pub fn reported(key: &str) -> Option<&'static str> {
    REPORTED.iter().find(|r| r.key == key).map(|r| r.value)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The printed frequencies and the numbers the figures draw are the same numbers, and each
    /// period is the frequency's 2π/ω to the digits the paper prints.
    #[test]
    fn the_printed_values_agree_with_the_numbers() {
        let parse = |key| reported(key).unwrap().parse::<f64>().unwrap();
        assert_eq!(parse("theta_omega_first"), THETA_OMEGA_FIRST);
        assert_eq!(parse("theta_omega_last"), THETA_OMEGA_LAST);
        let two_pi = 2.0 * std::f64::consts::PI;
        assert!((two_pi / THETA_OMEGA_FIRST - parse("theta_period_first_s")).abs() < 0.005);
        assert!((two_pi / THETA_OMEGA_LAST - parse("theta_period_last_s")).abs() < 0.0005);
    }

    #[test]
    fn every_key_is_reported_once() {
        let mut keys: Vec<_> = REPORTED.iter().map(|r| r.key).collect();
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), REPORTED.len());
        assert_eq!(reported("wall_s"), None);
    }
}
