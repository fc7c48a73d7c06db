//! The normal force over time: its samples, with its located extrema among them.
//!
//! The trajectory's sampling (1 kHz for the paper's scene) is too coarse for the ends of the
//! run, where a force peak lasts a fraction of a millisecond; and the full samples of a 100 s
//! run at 20 kHz would not fit in memory comfortably. So the sound runs its own simulation and
//! keeps only what it needs: the time and `N/mg`. Samples alone cut the top off a sharp
//! peak (at the end of the paper's run, 20 kHz samples read peaks of ~1400 mg as 115–1371),
//! so the run also locates every maximum and minimum of `N` on the integrator's dense
//! output (`equations::hybrid::extrema`) and puts them into the trace between the samples:
//! a peak's height, and the minima between peaks, are then exact whatever the sampling rate.

use equations::record::{Stop, StopKind};
use equations::{DiskConfig, DiskObserver, DiskRunner, DiskSample, SimError};
use equations::{Extremum, Watched};

use super::SoundError;
use crate::eval::Backend;
use crate::run::model::{choose_for, with_models, ModelChoice, ModelsTask};
use crate::scene::Scene;
use equations::record::Quantity;

/// Most force samples one run may keep (about 0.8 GB of memory).
pub const MAX_TRACE_SAMPLES: f64 = 5e7;

/// `N/mg` at increasing times: samples, and possibly located extrema among them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ForceTrace {
    t: Vec<f64>,
    n_over_mg: Vec<f64>,
    /// Whether each point is a located extremum (exact) rather than a sample.
    located: Vec<bool>,
}

/// Why a sequence of samples is not a force trace.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum TraceError {
    /// The two columns differ in length.
    #[error("{times} times but {values} values")]
    LengthMismatch {
        /// Number of times.
        times: usize,
        /// Number of values.
        values: usize,
    },
    /// A time or a value is NaN or infinite.
    #[error("sample {index} is not finite: t = {t}, N/mg = {value}")]
    NotFinite {
        /// Index of the sample.
        index: usize,
        /// Its time.
        t: f64,
        /// Its value.
        value: f64,
    },
    /// The times do not increase strictly (among samples), or decrease (with extrema added).
    #[error("time does not increase at sample {index}: {previous} then {t}")]
    TimeNotIncreasing {
        /// Index of the sample.
        index: usize,
        /// The time before it.
        previous: f64,
        /// Its time.
        t: f64,
    },
}

/// Checks a trace's columns: same length, finite, times increasing (strictly if `strict`).
fn check_columns(t: &[f64], n_over_mg: &[f64], strict: bool) -> Result<(), TraceError> {
    if t.len() != n_over_mg.len() {
        return Err(TraceError::LengthMismatch {
            times: t.len(),
            values: n_over_mg.len(),
        });
    }
    for (index, (&ti, &v)) in t.iter().zip(n_over_mg).enumerate() {
        if !ti.is_finite() || !v.is_finite() {
            return Err(TraceError::NotFinite {
                index,
                t: ti,
                value: v,
            });
        }
        if index > 0 && (ti < t[index - 1] || (strict && ti == t[index - 1])) {
            return Err(TraceError::TimeNotIncreasing {
                index,
                previous: t[index - 1],
                t: ti,
            });
        }
    }
    Ok(())
}

impl ForceTrace {
    /// A trace of samples from its two columns, checked: same length, finite, strictly
    /// increasing times.
    pub fn new(t: Vec<f64>, n_over_mg: Vec<f64>) -> Result<ForceTrace, TraceError> {
        check_columns(&t, &n_over_mg, true)?;
        let located = vec![false; t.len()];
        Ok(ForceTrace {
            t,
            n_over_mg,
            located,
        })
    }

    /// The samples with the located extrema `(t, N/mg)` (in time order) merged in. Two points
    /// may share a time: at a mode switch `N` jumps, and the values on either side are both
    /// extrema (an extremum at a sample's time follows the sample). An extremum outside the
    /// samples' span (by round-off: the run's last step, in regularised time, can end an ulp
    /// past the end time) is moved to its edge, so the trace spans what the samples span.
    pub fn with_extrema(self, extrema: &[(f64, f64)]) -> Result<ForceTrace, TraceError> {
        let (t, x): (Vec<f64>, Vec<f64>) = extrema.iter().copied().unzip();
        check_columns(&t, &x, false)?;
        let inside = |te: f64| match self.span() {
            Some(span) => te.clamp(span.start, span.end),
            None => te,
        };
        let len = self.len() + extrema.len();
        let mut merged = ForceTrace {
            t: Vec::with_capacity(len),
            n_over_mg: Vec::with_capacity(len),
            located: Vec::with_capacity(len),
        };
        let mut located = extrema.iter().peekable();
        for ((&ts, &xs), &exact) in self.t.iter().zip(&self.n_over_mg).zip(&self.located) {
            while let Some(&&(te, xe)) = located.peek().filter(|e| e.0 < ts) {
                merged.push(inside(te), xe, true);
                located.next();
            }
            merged.push(ts, xs, exact);
        }
        for &(te, xe) in located {
            merged.push(inside(te), xe, true);
        }
        Ok(merged)
    }

    /// The samples alone, without the located extrema.
    pub fn samples(&self) -> ForceTrace {
        let keep = |v: &[f64]| -> Vec<f64> {
            v.iter()
                .zip(&self.located)
                .filter(|(_, &l)| !l)
                .map(|(&x, _)| x)
                .collect()
        };
        let (t, n_over_mg) = (keep(&self.t), keep(&self.n_over_mg));
        let located = vec![false; t.len()];
        ForceTrace {
            t,
            n_over_mg,
            located,
        }
    }

    fn push(&mut self, t: f64, n_over_mg: f64, located: bool) {
        self.t.push(t);
        self.n_over_mg.push(n_over_mg);
        self.located.push(located);
    }

    /// Whether point `i` is a located extremum (its time and value exact) rather than a
    /// sample.
    pub fn is_located(&self, i: usize) -> bool {
        self.located.get(i).copied().unwrap_or(false)
    }

    /// Number of located extrema in the trace.
    pub fn located_count(&self) -> usize {
        self.located.iter().filter(|&&l| l).count()
    }

    /// The times (s).
    pub fn t(&self) -> &[f64] {
        &self.t
    }

    /// `N/mg` at those times.
    pub fn n_over_mg(&self) -> &[f64] {
        &self.n_over_mg
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether there are no samples.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// First and last time, if any.
    pub fn span(&self) -> Option<TimeSpan> {
        Some(TimeSpan {
            start: *self.t.first()?,
            end: *self.t.last()?,
        })
    }
}

/// A closed interval of simulated time (s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeSpan {
    /// Start (s).
    pub start: f64,
    /// End (s).
    pub end: f64,
}

impl TimeSpan {
    /// `end − start`.
    pub fn length(&self) -> f64 {
        self.end - self.start
    }
}

/// A finished run seen from the sound's side.
#[derive(Clone, Debug)]
pub struct ForceRun {
    /// `N/mg` over the run: the samples and the located extrema.
    pub trace: ForceTrace,
    /// Samples in the trace (the rest are located extrema).
    pub samples: usize,
    /// Why the run ended.
    pub stop_reason: StopKind,
    /// Details of the stop.
    pub stop_detail: String,
    /// The models that ran, and why.
    pub model: ModelChoice,
}

/// Keeps `(t, N/mg)` of every sample and of every located extremum of `N`.
struct ForceObserver {
    mg: f64,
    t: Vec<f64>,
    n_over_mg: Vec<f64>,
    extrema: Vec<(f64, f64)>,
}

impl DiskObserver for ForceObserver {
    fn on_sample(&mut self, s: &DiskSample) {
        // A trace's times increase strictly; a repeated time (a sample falling on a switch
        // can be delivered from both sides) keeps the first.
        if self.t.last().is_some_and(|&last| s.t <= last) {
            return;
        }
        self.t.push(s.t);
        self.n_over_mg.push(s.force.normal / self.mg);
    }

    fn wants_extrema(&self) -> bool {
        true
    }

    fn on_extremum(&mut self, e: &Extremum) {
        if e.quantity == Watched::NormalForce {
            self.extrema.push((e.t, e.value / self.mg));
        }
    }
}

/// The sound's simulation: keeps `N/mg` of every sample; returns the stop's name and detail.
struct Recording<'a> {
    scene: &'a Scene,
    rate: f64,
    observer: &'a mut ForceObserver,
}

impl ModelsTask for Recording<'_> {
    type Output = Result<(StopKind, String), SimError>;

    fn run(self, models: &dyn DiskRunner) -> Self::Output {
        let config = DiskConfig {
            sample_rate: Some(self.rate),
            ..self.scene.config
        };
        let outcome = models.simulate(&config, &self.scene.initial, self.observer)?;
        let stop = Stop::of(&outcome, config.allowed);
        Ok((stop.kind, stop.detail))
    }
}

/// Simulates `scene` and keeps `N/mg` at `rate` samples per second and at its located
/// extrema.
pub fn record_force(scene: &Scene, backend: Backend, rate: f64) -> Result<ForceRun, SoundError> {
    let t_end = scene.file.settings.run.t_end;
    if !(rate.is_finite() && rate > 0.0) {
        return Err(SoundError::Setting {
            name: "force-rate",
            value: rate,
            reason: "must be a positive number of samples per second",
        });
    }
    if t_end * rate > MAX_TRACE_SAMPLES {
        return Err(SoundError::TraceTooLong {
            t_end,
            rate,
            max_samples: MAX_TRACE_SAMPLES,
        });
    }
    let params = scene.params;
    let mut observer = ForceObserver {
        mg: params.weight(),
        t: Vec::with_capacity((t_end * rate) as usize + 2),
        n_over_mg: Vec::with_capacity((t_end * rate) as usize + 2),
        extrema: Vec::new(),
    };
    // The sound needs N only: the pruned models whenever the air is still.
    let model = choose_for(scene, backend, &[Quantity::N], "the sound");
    let task = Recording {
        scene,
        rate,
        observer: &mut observer,
    };
    let stop = with_models(model.model, params, scene.config.chart(), task)
        .map_err(|e| e.to_string())
        .and_then(|r| r.map_err(|e| e.to_string()));
    let (stop_reason, stop_detail) = stop.map_err(|message| SoundError::Simulation { message })?;
    // In time order (an extremum inside a step can be found after one at the step's end).
    let mut extrema = observer.extrema;
    extrema.sort_by(|a, b| a.0.total_cmp(&b.0));
    let sampled = ForceTrace::new(observer.t, observer.n_over_mg)?;
    let samples = sampled.len();
    let trace = sampled.with_extrema(&extrema)?;
    Ok(ForceRun {
        trace,
        samples,
        stop_reason,
        stop_detail,
        model,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_columns_are_named() {
        assert_eq!(
            ForceTrace::new(vec![0.0, 1.0], vec![1.0]),
            Err(TraceError::LengthMismatch {
                times: 2,
                values: 1
            })
        );
        assert!(matches!(
            ForceTrace::new(vec![0.0, 1.0], vec![1.0, f64::NAN]),
            Err(TraceError::NotFinite { index: 1, .. })
        ));
        assert_eq!(
            ForceTrace::new(vec![0.0, 1.0, 1.0], vec![1.0; 3]),
            Err(TraceError::TimeNotIncreasing {
                index: 2,
                previous: 1.0,
                t: 1.0
            })
        );
        let ok = ForceTrace::new(vec![0.0, 0.5], vec![1.0, 2.0]).unwrap();
        assert_eq!(ok.span().unwrap().length(), 0.5);
        assert!(matches!(
            ok.with_extrema(&[(0.4, 2.0), (0.3, 1.0)]),
            Err(TraceError::TimeNotIncreasing { index: 1, .. })
        ));
    }

    #[test]
    fn extrema_are_merged_between_the_samples_in_time_order() {
        let samples = ForceTrace::new(vec![0.0, 1.0, 2.0], vec![1.0, 3.0, 1.0]).unwrap();
        // A peak between samples, a jump at a sample's time (two values), one an ulp after
        // the end.
        let late = 2.0f64.next_up();
        let merged = samples
            .clone()
            .with_extrema(&[(0.8, 4.0), (1.0, 3.5), (1.0, 0.5), (late, 0.2)])
            .unwrap();
        assert_eq!(merged.t(), [0.0, 0.8, 1.0, 1.0, 1.0, 2.0, 2.0]);
        assert_eq!(merged.n_over_mg(), [1.0, 4.0, 3.0, 3.5, 0.5, 1.0, 0.2]);
        let located: Vec<bool> = (0..merged.len()).map(|i| merged.is_located(i)).collect();
        assert_eq!(located, [false, true, false, true, true, false, true]);
        assert_eq!(merged.located_count(), 4);
        assert_eq!(merged.samples(), samples);
    }
}
