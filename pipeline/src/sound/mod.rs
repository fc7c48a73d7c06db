//! `eulerdisk sound`: hear the rattle.
//!
//! The paper's claim is that the sharp peaks of the normal force `N(t)`, which come faster
//! and faster as the disk settles, are the rattle one hears. To let a listener judge, the
//! pipeline is: simulate and keep `N/mg`, sampled and at its located extrema ([`trace`]) →
//! pick the major peaks with a written-down rule ([`peaks`]) → measure their rate ([`rate`])
//! → render each peak
//! as a knock on a resonance into a WAV ([`mod@render`]) → show the sound's spectrogram and the
//! rate against the paper's numbers ([`mod@spectrogram`], `figures.rs`). Each stage is a plain
//! function of the previous stage's data, so each is tested on synthetic input with a known
//! answer.

mod figures;
mod files;
pub mod peaks;
pub mod rate;
pub mod render;
pub mod spectrogram;
mod summary;
pub mod trace;

use std::path::{Path, PathBuf};

use crate::eval::Backend;
use crate::output::atomic::{write_bytes_atomic, WriteError};
use crate::run::provenance::is_papers_scene;
use crate::scene::Scene;
use peaks::{major_peaks, Peak, PeakRule, PeakRuleError};
use rate::{rate_between, sliding_rates, PeakRate};
use render::{render, RenderError, RenderOptions};
use spectrogram::{spectrogram, SpectrogramError, StftSettings};
use summary::SoundSummary;
use trace::{record_force, ForceTrace, TimeSpan, TraceError};

/// Everything the sound needs besides the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SoundOptions {
    /// Samples per second of `N/mg` for the peak search (between its located extrema).
    pub force_rate: f64,
    /// What a major peak is.
    pub rule: PeakRule,
    /// How the sound is made.
    pub render: RenderOptions,
    /// Width of the windows of the rate (s).
    pub rate_window: f64,
    /// Step between the windows of the rate (s).
    pub rate_step: f64,
    /// The spectrogram's transform.
    pub stft: StftSettings,
    /// Highest frequency in the spectrogram figure (Hz).
    pub spectrogram_max_hz: f64,
    /// Whether to draw the figures.
    pub figures: bool,
}

impl Default for SoundOptions {
    fn default() -> Self {
        SoundOptions {
            force_rate: 20_000.0,
            rule: PeakRule::default(),
            render: RenderOptions::default(),
            rate_window: 1.0,
            rate_step: 0.25,
            stft: StftSettings::default(),
            spectrogram_max_hz: 6000.0,
            figures: true,
        }
    }
}

/// Why the sound could not be made.
#[derive(Debug, thiserror::Error)]
pub enum SoundError {
    /// A setting is out of range.
    #[error("invalid setting `{name}` = {value}: {reason}")]
    Setting {
        /// The setting.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        reason: &'static str,
    },
    /// The force trace would not fit in memory.
    #[error(
        "{t_end} s at {rate} samples/s exceeds {max_samples} force samples; lower --force-rate"
    )]
    TraceTooLong {
        /// The run's end time (s).
        t_end: f64,
        /// The force sampling rate (1/s).
        rate: f64,
        /// The most samples allowed.
        max_samples: f64,
    },
    /// The simulation failed.
    #[error("the simulation failed: {message}")]
    Simulation {
        /// What went wrong.
        message: String,
    },
    /// The simulation's samples are not a valid trace.
    #[error("force trace: {0}")]
    Trace(#[from] TraceError),
    /// The peak rule is invalid.
    #[error(transparent)]
    Peaks(#[from] PeakRuleError),
    /// The sound cannot be rendered.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// The spectrogram cannot be computed.
    #[error(transparent)]
    Spectrogram(#[from] SpectrogramError),
    /// The WAV encoder failed.
    #[error("cannot encode the WAV: {message}")]
    Wav {
        /// The encoder's message.
        message: String,
    },
    /// The output directory cannot be created.
    #[error("cannot create the output directory {}: {source}", path.display())]
    OutDir {
        /// The directory.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// An output file cannot be written.
    #[error(transparent)]
    Write(#[from] WriteError),
}

/// The peaks of a trace and how fast they come.
#[derive(Clone, Debug, PartialEq)]
pub struct PeakAnalysis {
    /// The trace's time span.
    pub span: TimeSpan,
    /// The major peaks, in time order.
    pub peaks: Vec<Peak>,
    /// Rates in sliding windows.
    pub rates: Vec<PeakRate>,
    /// The rate in the first second of the trace.
    pub first_second: PeakRate,
    /// The rate in the last second of the trace.
    pub last_second: PeakRate,
}

/// Finds the major peaks of `trace` and their rates.
pub fn analyse(trace: &ForceTrace, opts: &SoundOptions) -> Result<PeakAnalysis, SoundError> {
    for (name, value) in [
        ("rate-window", opts.rate_window),
        ("rate-step", opts.rate_step),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return Err(SoundError::Setting {
                name,
                value,
                reason: "must be a positive time",
            });
        }
    }
    let span = trace.span().ok_or(SoundError::Simulation {
        message: "the run produced no samples".into(),
    })?;
    let peaks = major_peaks(trace, &opts.rule)?;
    let rates = sliding_rates(&peaks, span, opts.rate_window, opts.rate_step);
    let first_second = rate_between(&peaks, span.start, span.start + 1.0);
    let last_second = rate_between(&peaks, span.end - 1.0, span.end);
    Ok(PeakAnalysis {
        span,
        peaks,
        rates,
        first_second,
        last_second,
    })
}

/// The WAV's file name: the time compression is part of it.
pub fn wav_name(speed: f64) -> String {
    if speed == 1.0 {
        "rattle.wav".to_string()
    } else {
        format!("rattle_speed{speed}x.wav")
    }
}

/// What `eulerdisk sound` produced.
#[derive(Clone, Debug)]
pub struct SoundReport {
    /// The summary (also written as `sound_summary.json`).
    pub summary: SoundSummary,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// Simulates `scene`, writes the sound, the peak tables, the figures and the summary into
/// `out_dir`.
pub fn sound_scene(
    scene: &Scene,
    backend: Backend,
    opts: &SoundOptions,
    out_dir: &Path,
) -> Result<SoundReport, SoundError> {
    std::fs::create_dir_all(out_dir).map_err(|source| SoundError::OutDir {
        path: out_dir.to_path_buf(),
        source,
    })?;
    // Settings are checked before the simulation, which may take a while.
    opts.render.validate()?;
    opts.rule.validate()?;
    let run = record_force(scene, backend, opts.force_rate)?;
    let analysis = analyse(&run.trace, opts)?;
    let sound = render(&analysis.peaks, analysis.span, &opts.render)?;
    let mut files = Vec::new();
    // The paper's numbers are shown for the paper's scene only.
    let paper = is_papers_scene(scene);
    let wav = out_dir.join(wav_name(opts.render.speed));
    let bytes = sound.wav_bytes().map_err(|e| SoundError::Wav {
        message: e.to_string(),
    })?;
    write_bytes_atomic(&wav, &bytes)?;
    files.push(wav.clone());
    files.extend(files::write_tables(
        &analysis,
        &sound,
        out_dir,
        scene.file.cli.output.format,
    )?);
    if opts.figures {
        let spec = spectrogram(&sound.as_f64(), f64::from(sound.sample_rate), opts.stft)?;
        let view = figures::SpectrogramView {
            title: format!(
                "Spectrogram of {}: the whole run",
                wav_name(opts.render.speed)
            ),
            max_hz: opts.spectrogram_max_hz,
            t_start: analysis.span.start,
            speed: opts.render.speed,
        };
        let path = out_dir.join("sound_spectrogram.png");
        figures::write_spectrogram(&spec, &view, &path)?;
        files.push(path);
        files.push(figures::write_rate_figure(
            &analysis.rates,
            &analysis.peaks,
            analysis.span,
            opts.rate_window,
            paper,
            out_dir,
        )?);
    }
    let summary = SoundSummary::new(scene, &run, &analysis, &sound, opts, &wav);
    files.push(summary::write_summary(&summary, out_dir)?);
    Ok(SoundReport { summary, files })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wav_names_carry_the_speed() {
        assert_eq!(wav_name(1.0), "rattle.wav");
        assert_eq!(wav_name(4.0), "rattle_speed4x.wav");
        assert_eq!(wav_name(2.5), "rattle_speed2.5x.wav");
    }
}
