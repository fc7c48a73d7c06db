//! What a listener should know about the sound: how the knocks were picked, how fast they
//! came at the start and at the end, and how that compares with the paper — in peaks per
//! second *and* as angular frequency, because the paper's "frequencies" are angular.

use std::path::{Path, PathBuf};

use equations::record::StopKind;

use serde::Serialize;

use super::figures::{PAPER_FIRST_SECOND, PAPER_LAST_SECOND, RECORDED};
use super::peaks::PeakRule;
use super::rate::PeakRate;
use super::render::Sound;
use super::trace::ForceRun;
use super::{PeakAnalysis, SoundOptions};
use crate::output::atomic::{write_bytes_atomic, WriteError};
use crate::run::provenance::is_papers_scene;
use crate::scene::Scene;

/// The rate of one window, in both readings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RateReading {
    /// Window start (s).
    pub from: f64,
    /// Window end (s).
    pub to: f64,
    /// Major peaks in the window.
    pub peaks: usize,
    /// Peaks per second (from the intervals).
    pub per_second: Option<f64>,
    /// `2π ·` peaks per second: the paper's reading (s⁻¹).
    pub angular: Option<f64>,
    /// Mean interval between peaks (s).
    pub period: Option<f64>,
}

impl From<PeakRate> for RateReading {
    fn from(r: PeakRate) -> Self {
        RateReading {
            from: r.from,
            to: r.to,
            peaks: r.peaks,
            per_second: r.per_second,
            angular: r.angular(),
            period: r.period(),
        }
    }
}

/// The paper's numbers the rates are compared with (angular, s⁻¹).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PaperRates {
    /// First second of the paper's run.
    pub first_second: f64,
    /// Last second of the paper's 100 s run.
    pub last_second: f64,
    /// The recording of the real toy.
    pub recorded: f64,
}

/// The summary of `eulerdisk sound` (written as `sound_summary.json`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SoundSummary {
    /// The scene.
    pub scene: String,
    /// First simulated time (s).
    pub t_start: f64,
    /// Last simulated time (s).
    pub t_end: f64,
    /// Why the run ended.
    pub stop_reason: StopKind,
    /// Details of the stop.
    pub stop_detail: String,
    /// The models that ran, e.g. `pruned (8 states)`.
    pub model: String,
    /// Why those models.
    pub model_reason: String,
    /// Samples of `N/mg` per second.
    pub force_rate: f64,
    /// Samples of `N/mg` kept.
    pub force_samples: usize,
    /// Located extrema of `N/mg` kept (exact; the peak heights and baselines among them).
    pub located_extrema: usize,
    /// The rule that defines a major peak.
    pub rule: RuleSettings,
    /// Major peaks found.
    pub peaks: usize,
    /// Of those, the peaks that are located extrema (the others are refined samples).
    pub peaks_located: usize,
    /// The rate in the first second.
    pub first_second: RateReading,
    /// The rate in the last second.
    pub last_second: RateReading,
    /// The paper's numbers, for the paper's scene only (`null` for another scene).
    pub paper: Option<PaperRates>,
    /// The WAV file.
    pub wav: String,
    /// Time compression (simulated seconds per second of sound; 1 is real time).
    pub speed: f64,
    /// Length of the sound (s).
    pub sound_seconds: f64,
    /// Samples per second of the WAV.
    pub sample_rate: u32,
    /// The resonance (Hz).
    pub ring_hz: f64,
    /// Its decay time constant (s).
    pub ring_decay_s: f64,
    /// The amplitude law, with `p` the peak's rise above its baseline in `N/mg`.
    pub amplitude: &'static str,
    /// The loudest knock's amplitude in the WAV (fraction of full scale; `peaks.csv` lists
    /// every knock's).
    pub amplitude_max: f64,
}

/// The peak rule as written in the summary.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RuleSettings {
    /// Half-width of the baseline window (s).
    pub window_s: f64,
    /// Smallest rise above the baseline (N/mg).
    pub min_prominence: f64,
    /// Smallest rise relative to the baseline.
    pub min_relative_prominence: f64,
    /// Half-width of the neighbourhood of rule 3 (s).
    pub neighbourhood_s: f64,
    /// Smallest rise as a share of the strongest in the neighbourhood.
    pub min_share_of_strongest: f64,
    /// Shortest time between peaks (s).
    pub refractory_s: f64,
}

impl From<PeakRule> for RuleSettings {
    fn from(r: PeakRule) -> Self {
        RuleSettings {
            window_s: r.window,
            min_prominence: r.min_prominence,
            min_relative_prominence: r.min_relative_prominence,
            neighbourhood_s: r.neighbourhood,
            min_share_of_strongest: r.min_share_of_strongest,
            refractory_s: r.refractory,
        }
    }
}

impl SoundSummary {
    /// Gathers the summary of one sound.
    pub fn new(
        scene: &Scene,
        run: &ForceRun,
        analysis: &PeakAnalysis,
        sound: &Sound,
        opts: &SoundOptions,
        wav: &Path,
    ) -> SoundSummary {
        SoundSummary {
            scene: scene.name.clone(),
            t_start: analysis.span.start,
            t_end: analysis.span.end,
            stop_reason: run.stop_reason,
            stop_detail: run.stop_detail.clone(),
            model: run.model.model.label(),
            model_reason: run.model.reason.clone(),
            force_rate: opts.force_rate,
            force_samples: run.samples,
            located_extrema: run.trace.located_count(),
            rule: opts.rule.into(),
            peaks: analysis.peaks.len(),
            peaks_located: analysis.peaks.iter().filter(|p| p.located).count(),
            first_second: analysis.first_second.into(),
            last_second: analysis.last_second.into(),
            paper: is_papers_scene(scene).then_some(PaperRates {
                first_second: PAPER_FIRST_SECOND,
                last_second: PAPER_LAST_SECOND,
                recorded: RECORDED,
            }),
            wav: wav
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            speed: opts.render.speed,
            sound_seconds: sound.seconds(),
            sample_rate: sound.sample_rate,
            ring_hz: opts.render.ring.hz,
            ring_decay_s: opts.render.ring.decay_s,
            amplitude: opts.render.compression.formula(),
            amplitude_max: analysis
                .peaks
                .iter()
                .map(|p| sound.knock_amplitude(p.prominence))
                .fold(0.0, f64::max),
        }
    }

    /// A few lines for the terminal.
    pub fn table(&self) -> String {
        let reading = |label: &str, r: &RateReading, paper: Option<String>| {
            let paper = paper.map_or(String::new(), |p| format!("; {p}"));
            match (r.per_second, r.angular, r.period) {
            (Some(rate), Some(angular), Some(period)) => format!(
                "{label} [{:.3}, {:.3}] s: {} peaks, {rate:.2} peaks/s, angular 2π·rate = {angular:.1} 1/s (period {period:.4} s){paper}\n",
                r.from, r.to, r.peaks
            ),
            _ => format!(
                "{label} [{:.3}, {:.3}] s: {} peaks, too few for a rate{paper}\n",
                r.from, r.to, r.peaks
            ),
        }
        };
        let speed = if self.speed == 1.0 {
            "real time".to_string()
        } else {
            format!("time compressed {}x", self.speed)
        };
        let mut s = format!(
            "scene `{}`: t = {} … {} s ({}); N/mg sampled at {} /s ({} samples) and at its {} located extrema\n",
            self.scene,
            self.t_start,
            self.t_end,
            self.stop_reason,
            self.force_rate,
            self.force_samples,
            self.located_extrema
        );
        s += &format!("models: {} ({})\n", self.model, self.model_reason);
        s += &format!(
            "{} major peaks ({} of them located extrema): local maxima of N/mg rising >= max({}, {}·|baseline|) above the higher flanking minimum within ±{} s,\n  >= {} of the largest rise within ±{} s, >= {} s apart\n",
            self.peaks,
            self.peaks_located,
            self.rule.min_prominence,
            self.rule.min_relative_prominence,
            self.rule.window_s,
            self.rule.min_share_of_strongest,
            self.rule.neighbourhood_s,
            self.rule.refractory_s
        );
        s += &reading(
            "first second",
            &self.first_second,
            self.paper.map(|p| format!("paper: {}", p.first_second)),
        );
        s += &reading(
            "last second ",
            &self.last_second,
            self.paper.map(|p| {
                format!(
                    "paper at 99–100 s: {}, recorded toy: {}",
                    p.last_second, p.recorded
                )
            }),
        );
        if self.paper.is_some() {
            s += "the paper's numbers are angular frequencies: 2π/0.14 s = 44.9, 2π/0.042 s = 149.6\n";
        }
        s += &format!(
            "sound: {} ({speed}), {:.2} s at {} Hz, 16-bit mono; each peak rings at {} Hz, decay {} ms, amplitude {} times one gain\n  (p: the peak's rise above its baseline in N/mg; the loudest knock {:.3} of full scale; peaks.csv lists each)\n",
            self.wav,
            self.sound_seconds,
            self.sample_rate,
            self.ring_hz,
            self.ring_decay_s * 1e3,
            self.amplitude,
            self.amplitude_max
        );
        s
    }
}

/// Writes `sound_summary.json` into `dir`; returns its path.
pub fn write_summary(summary: &SoundSummary, dir: &Path) -> Result<PathBuf, WriteError> {
    let path = dir.join("sound_summary.json");
    let json = serde_json::to_string_pretty(summary).map_err(|e| WriteError {
        path: path.clone(),
        source: std::io::Error::other(e),
    })?;
    write_bytes_atomic(&path, format!("{json}\n").as_bytes())?;
    Ok(path)
}
