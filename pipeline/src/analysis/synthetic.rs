//! A synthetic run with known answers, for testing the writers, figures and summary without
//! a simulation.
//!
//! θ oscillates as `θ0 + A e^(−λt) cos(ω t)` with a known period; the disk slides while θ̇ < 0
//! and rolls otherwise, so the transitions, ν and the slip follow a known pattern.

use std::f64::consts::PI;

use equations::DiskParams;

use crate::record::{RunData, Work};
use equations::record::{ContactForces, DiskState, Sample, Stop, StopKind};
use equations::Mode;
use equations::{Slip, TransitionRecord, Trigger};

/// What the synthetic run is made of.
#[derive(Clone, Copy, Debug)]
pub struct SyntheticRun {
    /// Oscillation period of θ (s).
    pub period: f64,
    /// Duration (s).
    pub t_end: f64,
    /// Sample rate (1/s).
    pub rate: f64,
}

impl SyntheticRun {
    /// θ̇ at `t`.
    fn theta(&self, t: f64) -> (f64, f64) {
        let w = 2.0 * PI / self.period;
        let (amp, lambda) = (0.2, 0.05);
        let e = amp * (-lambda * t).exp();
        let theta = 0.4 + e * (w * t).cos();
        let theta_dot = -lambda * e * (w * t).cos() - w * e * (w * t).sin();
        (theta, theta_dot)
    }

    fn sample(&self, t: f64, p: &DiskParams) -> Sample {
        let (theta, theta_dot) = self.theta(t);
        let mode = if theta_dot < 0.0 {
            Mode::Sliding
        } else {
            Mode::Rolling
        };
        let normal = p.m * p.g * (1.0 + 0.5 * (0.4 - theta));
        let nu = if mode == Mode::Sliding {
            p.mu_d
        } else {
            0.5 * (p.mu_d + p.mu_st)
        };
        Sample {
            t,
            mode,
            state: DiskState {
                z: p.a * theta.sin(),
                theta,
                omega_x: -20.0 * theta.sin(),
                omega_y: theta_dot,
                ..Default::default()
            },
            slip: Slip {
                speed: if mode == Mode::Sliding {
                    -1e-2 * theta_dot
                } else {
                    0.0
                },
                direction: 0.0,
            },
            forces: ContactForces {
                normal,
                friction: nu * normal,
                nu,
                r_x: nu * normal,
                r_y: 0.0,
            },
            energy: 1.0,
        }
    }

    fn fine(&self, t0: f64, t1: f64, p: &DiskParams) -> Vec<Sample> {
        let rate = 10.0 * self.rate;
        let n = ((t1 - t0) * rate).round() as usize;
        (0..=n)
            .map(|k| self.sample(t0 + k as f64 / rate, p))
            .collect()
    }

    /// The run's data.
    pub fn data(&self, p: &DiskParams) -> RunData {
        let n = (self.t_end * self.rate).round() as usize;
        let samples: Vec<Sample> = (0..=n)
            .map(|k| self.sample(k as f64 / self.rate, p))
            .collect();
        let mut events = Vec::new();
        for w in samples.windows(2) {
            if w[0].mode != w[1].mode {
                events.push(TransitionRecord {
                    t: w[1].t,
                    from: w[0].mode,
                    to: w[1].mode,
                    trigger: if w[1].mode == Mode::Sliding {
                        Trigger::FrictionLimit { ratio: p.mu_st }
                    } else {
                        Trigger::SlipStopped {
                            rolling_ratio: p.mu_st,
                            rolling_normal: w[1].forces.normal,
                        }
                    },
                    slip_direction: None,
                    rolling_direction: None,
                    drift: Default::default(),
                });
            }
        }
        RunData {
            first_second: self.fine(0.0, 1.0f64.min(self.t_end), p),
            last_second: self.fine((self.t_end - 1.0).max(0.0), self.t_end, p),
            samples,
            events,
            // No dense output: the summary and the figures read the samples.
            extrema: Vec::new(),
            stop: Some(Stop {
                t: self.t_end,
                mode: Mode::Rolling,
                kind: StopKind::EndTime,
                detail: String::new(),
            }),
            last_state: None,
            work: Work {
                steps: Some(10),
                rhs_evals: Some(100),
                wall_s: 0.5,
            },
            constraint_drift_max: Some(1e-12),
            model: Default::default(),
        }
    }
}
