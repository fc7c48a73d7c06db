//! The `sound` subcommand's arguments and its entry point.
//!
//! The scene flags are `run`'s own (flattened), so a scene is chosen, overridden and
//! validated exactly as for `eulerdisk run`. Only the output folder's default differs:
//! `out/sound`, so that a short run's `sound_summary.json` never sits beside a full run's
//! `summary.json` in `out/`.

use std::process::ExitCode;

use clap::{Args, ValueEnum};

use crate::args::{backend, RunArgs, EXIT_FAILED, EXIT_INPUT, EXIT_STOPPED};
use equations::record::StopKind;
use eulerdisk::{
    load_scene, sound_scene, Compression, PeakRule, RenderOptions, Ring, SoundError, SoundOptions,
};
use model_runtime::Readable;

/// Where `sound` writes unless `--out` says otherwise.
pub const DEFAULT_OUT: &str = "out/sound";

/// How a peak's rise sets its knock's amplitude, as `--compression` takes it (the library's
/// [`Compression`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum CompressionArg {
    /// `√p`.
    Sqrt,
    /// `ln(1 + p)`.
    Log,
}

impl From<CompressionArg> for Compression {
    fn from(compression: CompressionArg) -> Compression {
        match compression {
            CompressionArg::Sqrt => Compression::Sqrt,
            CompressionArg::Log => Compression::Log,
        }
    }
}

/// `eulerdisk sound`.
#[derive(Debug, Args)]
pub struct SoundArgs {
    /// The scene, the output directory and the solver, as for `run`.
    #[command(flatten)]
    pub run: RunArgs,
    /// Samples per second of N(t) searched for peaks, besides its located extrema (which give
    /// the peaks' heights exactly, whatever this rate).
    #[arg(long, default_value_t = 20_000.0)]
    pub force_rate: f64,
    /// Frequency of the resonance each force peak excites (Hz).
    #[arg(long, default_value_t = 2500.0)]
    pub ring_hz: f64,
    /// Decay time constant of that resonance (ms).
    #[arg(long, default_value_t = 8.0)]
    pub ring_decay_ms: f64,
    /// Play the run K times faster (the name of the WAV says so).
    #[arg(long, default_value_t = 1.0, value_name = "K")]
    pub speed: f64,
    /// Amplitude law of a knock, from the peak's located rise p above its baseline (N/mg).
    #[arg(long, value_enum, default_value_t = CompressionArg::Sqrt)]
    pub compression: CompressionArg,
    /// A major peak rises at least this much above its baseline (N/mg)...
    #[arg(long, default_value_t = PeakRule::default().min_prominence)]
    pub min_prominence: f64,
    /// ...and at least this fraction of the baseline's magnitude.
    #[arg(long, default_value_t = PeakRule::default().min_relative_prominence)]
    pub min_relative_prominence: f64,
    /// ...and at least this share of the largest rise within ±0.25 s.
    #[arg(long, default_value_t = PeakRule::default().min_share_of_strongest)]
    pub min_share_of_strongest: f64,
    /// Shortest time between two major peaks (ms).
    #[arg(long, default_value_t = PeakRule::default().refractory * 1e3)]
    pub refractory_ms: f64,
    /// Width of the windows of the peak rate (s).
    #[arg(long, default_value_t = 1.0)]
    pub rate_window: f64,
}

impl SoundArgs {
    /// The options these arguments ask for.
    pub fn options(&self) -> SoundOptions {
        let defaults = SoundOptions::default();
        SoundOptions {
            force_rate: self.force_rate,
            rule: PeakRule {
                min_prominence: self.min_prominence,
                min_relative_prominence: self.min_relative_prominence,
                min_share_of_strongest: self.min_share_of_strongest,
                refractory: self.refractory_ms / 1e3,
                ..PeakRule::default()
            },
            render: RenderOptions {
                ring: Ring {
                    hz: self.ring_hz,
                    decay_s: self.ring_decay_ms / 1e3,
                },
                compression: self.compression.into(),
                speed: self.speed,
                ..RenderOptions::default()
            },
            rate_window: self.rate_window,
            rate_step: (self.rate_window / 4.0).min(defaults.rate_step),
            figures: !self.run.no_figures,
            ..defaults
        }
    }
}

/// Runs `eulerdisk sound`: prints the summary, returns the exit code.
pub fn command(args: &SoundArgs) -> ExitCode {
    let out = args.run.out_dir(DEFAULT_OUT);
    let scene = match args
        .run
        .overrides()
        .and_then(|o| load_scene(&args.run.scene, &o))
    {
        Ok(s) => s,
        Err(err) => {
            eprintln!("error: {err}");
            return ExitCode::from(EXIT_INPUT);
        }
    };
    if !args.run.quiet {
        eprintln!(
            "scene `{}`: simulating {} s for its sound, output in {}",
            scene.name,
            Readable(scene.file.settings.run.t_end),
            out.display()
        );
    }
    match sound_scene(&scene, backend(args.run.reference), &args.options(), &out) {
        Ok(report) => {
            if !args.run.quiet {
                let said = format!(
                    "{}wrote {} files into {}\n",
                    report.summary.table(),
                    report.files.len(),
                    out.display()
                );
                if let Err(code) = crate::args::print_out(&said) {
                    return code;
                }
            }
            let s = &report.summary;
            if s.stop_reason == StopKind::EndTime {
                ExitCode::SUCCESS
            } else {
                eprintln!(
                    "the run stopped early ({}): {}",
                    s.stop_reason, s.stop_detail
                );
                ExitCode::from(EXIT_STOPPED)
            }
        }
        Err(err) => {
            eprintln!("error: {err}");
            let input = matches!(
                err,
                SoundError::Setting { .. }
                    | SoundError::TraceTooLong { .. }
                    | SoundError::Peaks(_)
                    | SoundError::Render(_)
            );
            ExitCode::from(if input { EXIT_INPUT } else { EXIT_FAILED })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Debug, Parser)]
    struct Wrapper {
        #[command(flatten)]
        sound: SoundArgs,
    }

    #[test]
    fn defaults_are_the_library_defaults() {
        let w = Wrapper::try_parse_from(["sound"]).unwrap();
        assert_eq!(w.sound.options(), SoundOptions::default());
        assert_eq!(w.sound.run.scene, eulerdisk::DEFAULT_SCENE);
        assert_eq!(
            w.sound.run.out_dir(DEFAULT_OUT),
            std::path::PathBuf::from("out/sound")
        );
    }

    #[test]
    fn flags_reach_the_options_and_the_scene() {
        let w = Wrapper::try_parse_from([
            "sound",
            "my-scene.toml",
            "--speed",
            "4",
            "--ring-hz",
            "3000",
            "--ring-decay-ms",
            "5",
            "--compression",
            "log",
            "--t-end",
            "5",
            "--no-figures",
        ])
        .unwrap();
        let o = w.sound.options();
        assert_eq!(o.render.speed, 4.0);
        assert_eq!(o.render.ring.hz, 3000.0);
        assert_eq!(o.render.ring.decay_s, 0.005);
        assert_eq!(o.render.compression, Compression::Log);
        assert!(!o.figures);
        assert_eq!(w.sound.run.scene, "my-scene.toml");
        assert_eq!(w.sound.run.t_end, Some(5.0));
    }
}
