//! `eulerdisk sound`: the WAV's format, peak detection on signals of known rate, the
//! spectrogram of a pure tone, and the knock rate of a short run of the paper's scene.

use std::f64::consts::{PI, TAU};

use eulerdisk::{
    analyse, load_scene, major_peaks, record_force, render, sound_scene, spectrogram, wav_name,
    Backend, ForceTrace, Override, PeakRule, RenderOptions, RunModel, SoundOptions, StftSettings,
    TimeSpan, DEFAULT_SCENE, HEADROOM,
};
use proptest::prelude::*;

const FORCE_RATE: f64 = 20_000.0;

/// `N/mg` of a disk whose inclination oscillates at `rate` per second: the paper's law (15)
/// `α3 + α4 / sin θ` with `θ = 0.3 + 0.27 cos(2π rate t + phase)` (minima 0.03 rad), and in
/// the half-periods around the largest inclinations small fast wiggles like those of a
/// sliding phase.
fn knock_train(rate: f64, phase: f64, seconds: f64) -> ForceTrace {
    let n = (seconds * FORCE_RATE) as usize;
    let t: Vec<f64> = (0..n).map(|i| i as f64 / FORCE_RATE).collect();
    let x = t
        .iter()
        .map(|&t| {
            let arg = TAU * rate * t + phase;
            let theta = 0.3 + 0.27 * arg.cos();
            let sliding = arg.cos() > 0.0;
            let wiggle = if sliding {
                0.004 * (TAU * 410.0 * t).sin()
            } else {
                0.0
            };
            0.7 + 0.01 / theta.sin() + wiggle
        })
        .collect();
    ForceTrace::new(t, x).unwrap()
}

/// Times in `[0, seconds)` where the train's θ is smallest.
fn minima(rate: f64, phase: f64, seconds: f64) -> Vec<f64> {
    // arg = π (mod 2π)  ⇔  t = ((2k + 1)π − phase) / (2π rate).
    (0..)
        .map(|k| ((2 * k + 1) as f64 * PI - phase) / (TAU * rate))
        .skip_while(|&t| t < 0.0)
        .take_while(|&t| t < seconds)
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn peak_detection_recovers_a_known_rate(rate in 5.0f64..30.0, phase in 0.0f64..TAU) {
        let seconds = 3.0;
        let trace = knock_train(rate, phase, seconds);
        // Minima within a sample or two of either end may or may not be sampled as local
        // maxima: both lists are compared inside.
        let edge = 2.0 / FORCE_RATE;
        let inside = |t: f64| t > edge && t < seconds - 2.0 * edge;
        let peaks: Vec<_> = major_peaks(&trace, &PeakRule::default())
            .unwrap()
            .into_iter()
            .filter(|p| inside(p.t))
            .collect();
        let expected: Vec<f64> = minima(rate, phase, seconds).into_iter().filter(|&t| inside(t)).collect();
        prop_assert_eq!(peaks.len(), expected.len(), "{:?} vs {:?}", peaks, expected);
        for (p, t) in peaks.iter().zip(&expected) {
            prop_assert!((p.t - t).abs() < 1e-5, "peak at {} expected {}", p.t, t);
        }
        // The rate of a window clear of both ends, as the analysis reports it.
        let analysis = analyse(&trace, &SoundOptions::default()).unwrap();
        let r = analysis
            .rates
            .iter()
            .find(|r| r.from >= 0.5 && r.to <= seconds - 0.5)
            .unwrap();
        prop_assert!((r.per_second.unwrap() / rate - 1.0).abs() < 1e-5, "{:?}", r);
    }
}

#[test]
fn rendered_wav_has_the_expected_format_length_and_no_clipping() {
    let seconds = 2.0;
    let trace = knock_train(12.0, 0.3, seconds);
    let opts = SoundOptions::default();
    let analysis = analyse(&trace, &opts).unwrap();
    assert_eq!(analysis.peaks.len(), 24);
    let sound = render(&analysis.peaks, analysis.span, &opts.render).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(wav_name(1.0));
    std::fs::write(&path, sound.wav_bytes().unwrap()).unwrap();

    let mut reader = hound::WavReader::open(&path).unwrap();
    let spec = reader.spec();
    assert_eq!(spec.sample_rate, 44_100);
    assert_eq!(spec.bits_per_sample, 16);
    assert_eq!(spec.channels, 1);
    assert_eq!(spec.sample_format, hound::SampleFormat::Int);
    let expected_len = analysis.span.length() / opts.render.speed * 44_100.0;
    let tail = opts.render.tail_samples();
    assert_eq!(
        reader.duration() as usize,
        expected_len.ceil() as usize + tail
    );
    let samples: Vec<i16> = reader.samples::<i16>().map(Result::unwrap).collect();
    assert_eq!(samples, sound.samples);
    let loudest = samples.iter().map(|s| s.unsigned_abs()).max().unwrap();
    assert_eq!(
        f64::from(loudest),
        (HEADROOM * 32767.0).round(),
        "normalised to the headroom"
    );
    assert!(loudest < i16::MAX as u16, "clipped");
}

#[test]
fn time_compression_shortens_the_sound() {
    let trace = knock_train(12.0, 0.3, 2.0);
    let opts = SoundOptions::default();
    let analysis = analyse(&trace, &opts).unwrap();
    let fast = RenderOptions {
        speed: 4.0,
        ..opts.render
    };
    let sound = render(&analysis.peaks, analysis.span, &fast).unwrap();
    assert_eq!(sound.knocks, 24);
    let body = (analysis.span.length() / 4.0 * 44_100.0).ceil() as usize;
    assert_eq!(sound.samples.len(), body + fast.tail_samples());
}

#[test]
fn spectrogram_of_a_pure_tone_peaks_at_its_bin() {
    let rate = 44_100.0;
    let settings = StftSettings::default();
    let bin_hz = rate / settings.frame as f64;
    // On a bin, and between two bins (nearest bin wins).
    for (hz, bin) in [
        (116.0 * bin_hz, 116),
        (1000.0, (1000.0 / bin_hz).round() as usize),
    ] {
        let signal: Vec<f64> = (0..44_100)
            .map(|i| 0.5 * (TAU * hz * i as f64 / rate).sin())
            .collect();
        let s = spectrogram(&signal, rate, settings).unwrap();
        assert!(!s.power_db.is_empty());
        for frame in 0..s.power_db.len() {
            assert_eq!(s.peak_bin(frame), Some(bin), "{hz} Hz, frame {frame}");
        }
    }
}

#[test]
fn short_paper_scene_reports_its_knock_rate() {
    let t_end = 3.0;
    let scene = load_scene(DEFAULT_SCENE, &[Override::new("run", "t_end", t_end)]).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let report = sound_scene(
        &scene,
        Backend::Generated,
        &SoundOptions::default(),
        dir.path(),
    )
    .unwrap();
    // Reported, not asserted against the paper (its numbers are for the ends of 100 s).
    println!("{}", report.summary.table());
    let s = &report.summary;
    assert_eq!(s.t_end, t_end);
    assert!(s.peaks > 0);
    let last = s.last_second.per_second.expect("a rate in the last second");
    assert!(last.is_finite() && last > 0.0);
    for name in [
        "rattle.wav",
        "peaks.csv",
        "peak_rate.csv",
        "sound_spectrogram.png",
        "sound_peak_rate.png",
        "sound_summary.json",
    ] {
        assert!(dir.path().join(name).is_file(), "{name} missing");
    }
    let peaks_csv = std::fs::read_to_string(dir.path().join("peaks.csv")).unwrap();
    assert_eq!(peaks_csv.lines().count(), s.peaks + 1);
    let span = TimeSpan {
        start: 0.0,
        end: t_end,
    };
    let wav = hound::WavReader::open(dir.path().join("rattle.wav")).unwrap();
    assert_eq!(
        wav.duration() as usize,
        SoundOptions::default().render.samples_for(span)
    );
}

/// The rows of `peaks.csv`: time, height, prominence, amplitude, located.
fn peak_rows(dir: &std::path::Path) -> Vec<[f64; 5]> {
    let text = std::fs::read_to_string(dir.join("peaks.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("t_s,N_over_mg,prominence,amplitude,located")
    );
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            v.try_into().unwrap()
        })
        .collect()
}

/// The knocks' heights and amplitudes come from the located extrema of N, so the sound at
/// 2 kHz, at the default 20 kHz and at 200 kHz has the same knocks, as loud (to 1e-6; the
/// issue asks for 1%). The samples alone at 2 kHz would cut the tops off by more than 1%.
#[test]
fn knock_amplitudes_do_not_depend_on_the_force_rate() {
    let scene = load_scene(DEFAULT_SCENE, &[Override::new("run", "t_end", 3.0)]).unwrap();
    let at = |force_rate: f64| {
        let dir = tempfile::tempdir().unwrap();
        let opts = SoundOptions {
            force_rate,
            figures: false,
            ..SoundOptions::default()
        };
        let report = sound_scene(&scene, Backend::Generated, &opts, dir.path()).unwrap();
        (peak_rows(dir.path()), report.summary)
    };
    let (fine, fine_summary) = at(200_000.0);
    assert!(fine.len() >= 20, "{} knocks", fine.len());
    assert!(fine.iter().all(|r| r[4] == 1.0), "every knock is located");
    for rate in [2000.0, FORCE_RATE] {
        let (rows, summary) = at(rate);
        assert_eq!(rows.len(), fine.len(), "knocks at {rate} /s");
        for (a, b) in rows.iter().zip(&fine) {
            assert!((a[0] - b[0]).abs() < 1e-9, "time {a:?} vs {b:?}");
            for k in 1..4 {
                assert!(
                    (a[k] - b[k]).abs() <= 1e-6 * b[k].abs(),
                    "column {k} at {rate} /s: {a:?} vs {b:?}"
                );
            }
        }
        assert!((summary.amplitude_max / fine_summary.amplitude_max - 1.0).abs() < 1e-6);
    }
    // The 2 kHz samples without the located extrema: the same knocks, lower.
    let run = record_force(&scene, Backend::Generated, 2000.0).unwrap();
    let samples = run.trace.samples();
    assert_eq!(samples.len(), run.samples);
    let sampled = major_peaks(&samples, &PeakRule::default()).unwrap();
    let shortfall = sampled
        .iter()
        .filter_map(|p| {
            let exact = fine.iter().find(|r| (r[0] - p.t).abs() < 1e-3)?;
            Some(1.0 - p.n_over_mg / exact[1])
        })
        .fold(0.0, f64::max);
    println!("largest shortfall of a 2 kHz sampled peak: {shortfall:.3}");
    assert!(shortfall > 0.01, "{shortfall}");
}

/// The full 100 s of the paper's scene (slow: run with `--ignored`). Writes into
/// `$EULERDISK_SOUND_OUT` when set, else into a temporary directory.
#[test]
#[ignore]
fn paper_scene_full_run_sound() {
    let scene = load_scene(DEFAULT_SCENE, &[]).unwrap();
    let keep = std::env::var_os("EULERDISK_SOUND_OUT").map(std::path::PathBuf::from);
    let tmp = tempfile::tempdir().unwrap();
    let dir = keep.unwrap_or_else(|| tmp.path().to_path_buf());
    let report = sound_scene(&scene, Backend::Generated, &SoundOptions::default(), &dir).unwrap();
    println!("{}", report.summary.table());
    assert!(report.summary.peaks > 0);
}

#[test]
fn time_compression_is_named_in_the_file_and_the_summary() {
    let scene = load_scene(DEFAULT_SCENE, &[Override::new("run", "t_end", 1.5)]).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let mut opts = SoundOptions {
        figures: false,
        ..SoundOptions::default()
    };
    opts.render.speed = 2.0;
    let report = sound_scene(&scene, Backend::Generated, &opts, dir.path()).unwrap();
    assert_eq!(report.summary.wav, "rattle_speed2x.wav");
    assert!(report.summary.table().contains("time compressed 2x"));
    let wav = hound::WavReader::open(dir.path().join("rattle_speed2x.wav")).unwrap();
    let span = TimeSpan {
        start: 0.0,
        end: 1.5,
    };
    assert_eq!(wav.duration() as usize, opts.render.samples_for(span));
    assert!(!dir.path().join("rattle.wav").exists());
}

/// The sound needs only `N`, so in still air it runs the pruned models: their force trace is
/// the hand-written reference's to within the integration error, and the summary says which
/// models ran and why. With air, the full models run and the reason names the setting.
#[test]
fn sound_runs_the_pruned_models_in_still_air() {
    let t_end = 0.5;
    let rate = 2000.0;
    let scene = load_scene(DEFAULT_SCENE, &[Override::new("run", "t_end", t_end)]).unwrap();
    let pruned = record_force(&scene, Backend::Generated, rate).unwrap();
    let reference = record_force(&scene, Backend::Reference, rate).unwrap();
    assert_eq!(
        pruned.model.model,
        RunModel::Pruned,
        "{}",
        pruned.model.reason
    );
    assert_eq!(reference.model.model, RunModel::Reference);
    // The samples: the located extrema between them may differ in the last digits.
    let (pruned_samples, reference_samples) = (pruned.trace.samples(), reference.trace.samples());
    assert_eq!(pruned_samples.t(), reference_samples.t());
    let worst = pruned_samples
        .n_over_mg()
        .iter()
        .zip(reference_samples.n_over_mg())
        .map(|(a, b)| (a - b).abs() / b.abs().max(1.0))
        .fold(0.0, f64::max);
    println!("largest difference of N/mg, pruned vs reference: {worst:e}");
    assert!(worst < 1e-6, "{worst:e}");

    let airy = load_scene(
        DEFAULT_SCENE,
        &[
            Override::new("run", "t_end", 0.05),
            Override::new("air", "mu_a", 0.01),
        ],
    )
    .unwrap();
    let full = record_force(&airy, Backend::Generated, rate).unwrap();
    assert_eq!(full.model.model, RunModel::Full);
    assert!(full.model.reason.contains("mu_a"), "{}", full.model.reason);
}
