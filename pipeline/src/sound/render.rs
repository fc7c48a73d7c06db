//! From force peaks to a sound.
//!
//! The rigid model gives the force on the disk, not its vibration, so the sound is a model of
//! the ear's side: each major peak is a knock that excites one decaying resonance of the
//! disk (a damped sinusoid, `ring.hz`, time constant `ring.decay_s`), started at the peak's
//! time. Knocks differ by orders of magnitude in height near the end of a run, so the
//! amplitude is a compressed function of the peak's rise above its baseline `p` (in `N/mg`):
//! `√p` ([`Compression::Sqrt`], the default) or `ln(1 + p)` ([`Compression::Log`]).
//! The sum is scaled so its largest magnitude is [`HEADROOM`] of full scale: never clipped.
//! A knock's amplitude in the WAV ([`Sound::knock_amplitude`], the `amplitude` column of
//! `peaks.csv`) is that law times the one gain of the whole sound. The peak heights and their
//! baselines are located extrema of `N` (`super::peaks`), so the amplitudes do not depend on
//! the rate at which `N` is sampled.
//!
//! A run of 100 s is a long listen: `speed = K` plays the peak times `K` times faster (the
//! resonance itself keeps its pitch and decay), and the output names say so.

use std::f64::consts::TAU;
use std::io::Cursor;

use super::peaks::Peak;
use super::trace::TimeSpan;

/// The largest sample magnitude, as a fraction of 16-bit full scale (−1 dBFS).
pub const HEADROOM: f64 = 0.891;
/// Longest sound rendered (s): one hour.
pub const MAX_SECONDS: f64 = 3600.0;
/// Each resonance is cut after this many time constants: `e^−10.4 < 2⁻¹⁵`, below one step of
/// 16-bit audio, so the cut is inaudible.
pub const TAIL_DECAYS: f64 = 10.4;

/// How the peak's rise sets its knock's amplitude.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compression {
    /// `√p`.
    Sqrt,
    /// `ln(1 + p)`.
    Log,
}

impl Compression {
    /// The amplitude of a knock whose peak rises `p` above its baseline.
    pub fn amplitude(self, p: f64) -> f64 {
        let p = p.max(0.0);
        match self {
            Compression::Sqrt => p.sqrt(),
            Compression::Log => p.ln_1p(),
        }
    }

    /// The formula, for summaries.
    pub fn formula(self) -> &'static str {
        match self {
            Compression::Sqrt => "sqrt(p)",
            Compression::Log => "ln(1 + p)",
        }
    }
}

/// The resonance each knock excites.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ring {
    /// Frequency (Hz).
    pub hz: f64,
    /// Time constant of the exponential decay (s).
    pub decay_s: f64,
}

/// How the sound is made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    /// Samples per second of the WAV.
    pub sample_rate: u32,
    /// The resonance.
    pub ring: Ring,
    /// Amplitude law.
    pub compression: Compression,
    /// Time compression: simulated seconds per second of sound.
    pub speed: f64,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            sample_rate: 44_100,
            ring: Ring {
                hz: 2500.0,
                decay_s: 0.008,
            },
            compression: Compression::Sqrt,
            speed: 1.0,
        }
    }
}

/// Why a sound cannot be rendered.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum RenderError {
    /// A setting is out of range.
    #[error("sound setting `{name}` = {value}: {reason}")]
    Setting {
        /// The setting.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        reason: &'static str,
    },
    /// The ring's frequency cannot be represented at this sample rate.
    #[error("ring frequency {hz} Hz is not below the Nyquist frequency {nyquist} Hz")]
    RingAboveNyquist {
        /// The ring's frequency (Hz).
        hz: f64,
        /// Half the sample rate (Hz).
        nyquist: f64,
    },
    /// The sound would be too long.
    #[error("the sound would last {seconds} s (longest: {max} s); raise --speed")]
    TooLong {
        /// Its length (s).
        seconds: f64,
        /// The longest allowed (s).
        max: f64,
    },
}

/// A rendered sound.
#[derive(Clone, Debug, PartialEq)]
pub struct Sound {
    /// 16-bit mono samples.
    pub samples: Vec<i16>,
    /// Samples per second.
    pub sample_rate: u32,
    /// The scale from the unnormalised sum to full scale (0 when silent).
    pub gain: f64,
    /// Knocks rendered.
    pub knocks: usize,
    /// The amplitude law the knocks were rendered with.
    pub compression: Compression,
}

impl Sound {
    /// Length (s).
    pub fn seconds(&self) -> f64 {
        self.samples.len() as f64 / f64::from(self.sample_rate)
    }

    /// The amplitude, as a fraction of full scale, of the knock of a peak that rises
    /// `prominence` above its baseline: the amplitude law times the sound's gain (the sample
    /// magnitude it reaches alone, before the tails of earlier knocks add to it, is this
    /// times the resonance's first crest, `e^(−1/(4 f τ))`, 0.988 by default).
    pub fn knock_amplitude(&self, prominence: f64) -> f64 {
        self.compression.amplitude(prominence) * self.gain / 32767.0
    }

    /// The samples as floats in [−1, 1].
    pub fn as_f64(&self) -> Vec<f64> {
        self.samples
            .iter()
            .map(|&s| f64::from(s) / 32768.0)
            .collect()
    }

    /// The sound as a WAV file (16-bit PCM, mono).
    pub fn wav_bytes(&self) -> Result<Vec<u8>, hound::Error> {
        let spec = hound::WavSpec {
            channels: 1,
            sample_rate: self.sample_rate,
            bits_per_sample: 16,
            sample_format: hound::SampleFormat::Int,
        };
        let mut cursor = Cursor::new(Vec::with_capacity(44 + 2 * self.samples.len()));
        {
            let mut writer = hound::WavWriter::new(&mut cursor, spec)?;
            for &s in &self.samples {
                writer.write_sample(s)?;
            }
            writer.finalize()?;
        }
        Ok(cursor.into_inner())
    }
}

impl RenderOptions {
    /// Checks every setting.
    pub fn validate(&self) -> Result<(), RenderError> {
        let setting = |name, value: f64, reason| RenderError::Setting {
            name,
            value,
            reason,
        };
        if self.sample_rate == 0 {
            return Err(setting("sample-rate", 0.0, "must be positive"));
        }
        if !(self.speed.is_finite() && self.speed > 0.0) {
            return Err(setting("speed", self.speed, "must be a positive number"));
        }
        if !(self.ring.hz.is_finite() && self.ring.hz > 0.0) {
            return Err(setting(
                "ring-hz",
                self.ring.hz,
                "must be a positive frequency",
            ));
        }
        if !(self.ring.decay_s.is_finite() && self.ring.decay_s > 0.0) {
            return Err(setting(
                "ring-decay",
                self.ring.decay_s,
                "must be a positive time",
            ));
        }
        let nyquist = 0.5 * f64::from(self.sample_rate);
        if self.ring.hz >= nyquist {
            return Err(RenderError::RingAboveNyquist {
                hz: self.ring.hz,
                nyquist,
            });
        }
        Ok(())
    }

    /// Samples of one knock's resonance.
    pub fn tail_samples(&self) -> usize {
        (TAIL_DECAYS * self.ring.decay_s * f64::from(self.sample_rate)).ceil() as usize
    }

    /// The sound's length in samples for a run over `span`: the compressed span plus one
    /// knock's tail.
    pub fn samples_for(&self, span: TimeSpan) -> usize {
        let body = (span.length().max(0.0) / self.speed * f64::from(self.sample_rate)).ceil();
        body as usize + self.tail_samples()
    }
}

/// Renders the knocks of `peaks` over the run's `span`.
pub fn render(peaks: &[Peak], span: TimeSpan, opts: &RenderOptions) -> Result<Sound, RenderError> {
    opts.validate()?;
    let rate = f64::from(opts.sample_rate);
    let seconds = span.length().max(0.0) / opts.speed;
    if seconds > MAX_SECONDS {
        return Err(RenderError::TooLong {
            seconds,
            max: MAX_SECONDS,
        });
    }
    let len = opts.samples_for(span);
    let tail = opts.tail_samples();
    // One knock's waveform, shared by all (they differ only in amplitude and start).
    let w = TAU * opts.ring.hz / rate;
    let knock: Vec<f64> = (0..tail)
        .map(|k| (-(k as f64) / (opts.ring.decay_s * rate)).exp() * (w * k as f64).sin())
        .collect();
    let mut sum = vec![0.0f64; len];
    let mut knocks = 0;
    for p in peaks {
        if !(span.start..=span.end).contains(&p.t) {
            continue;
        }
        let start = (((p.t - span.start) / opts.speed) * rate).round() as usize;
        let amplitude = opts.compression.amplitude(p.prominence);
        for (out, k) in sum[start.min(len)..].iter_mut().zip(&knock) {
            *out += amplitude * k;
        }
        knocks += 1;
    }
    let largest = sum.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let gain = if largest > 0.0 {
        HEADROOM * 32767.0 / largest
    } else {
        0.0
    };
    let samples = sum
        .iter()
        .map(|v| (v * gain).round().clamp(-32767.0, 32767.0) as i16)
        .collect();
    Ok(Sound {
        samples,
        sample_rate: opts.sample_rate,
        gain,
        knocks,
        compression: opts.compression,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn peak(t: f64, prominence: f64) -> Peak {
        Peak {
            t,
            n_over_mg: 1.0 + prominence,
            prominence,
            located: true,
        }
    }

    #[test]
    fn knocks_start_at_their_peaks_and_scale_by_the_law() {
        let span = TimeSpan {
            start: 10.0,
            end: 11.0,
        };
        let opts = RenderOptions::default();
        let s = render(&[peak(10.25, 4.0), peak(10.75, 1.0)], span, &opts).unwrap();
        assert_eq!(s.knocks, 2);
        let first = (0.25 * 44_100.0) as usize;
        assert!(s.samples[..first].iter().all(|&v| v == 0));
        assert!(s.samples[first + 1..first + 10].iter().any(|&v| v != 0));
        // The taller knock (√4 = 2) reaches full headroom; the other (√1) half of it.
        let max_in = |a: usize, b: usize| {
            s.samples[a..b]
                .iter()
                .map(|v| v.unsigned_abs())
                .max()
                .unwrap()
        };
        let loud = max_in(first, first + 2000);
        let soft = max_in(first + 22_050, first + 24_000);
        assert_eq!(f64::from(loud), (HEADROOM * 32767.0).round());
        assert!(
            (f64::from(soft) / f64::from(loud) - 0.5).abs() < 2e-3,
            "{soft} {loud}"
        );
        // The reported amplitudes: the loud knock's, times the resonance's highest sample, is
        // the headroom; the soft one's is half of it.
        let w = TAU * opts.ring.hz / 44_100.0;
        let crest = (0..100)
            .map(|k| (-(k as f64) / (opts.ring.decay_s * 44_100.0)).exp() * (w * k as f64).sin())
            .fold(0.0, f64::max);
        assert!((s.knock_amplitude(4.0) * crest - HEADROOM).abs() < 1e-12);
        assert_eq!(s.knock_amplitude(1.0), 0.5 * s.knock_amplitude(4.0));
    }

    #[test]
    fn silence_without_peaks_is_zero_not_nan() {
        let span = TimeSpan {
            start: 0.0,
            end: 0.5,
        };
        let s = render(&[], span, &RenderOptions::default()).unwrap();
        assert_eq!(s.gain, 0.0);
        assert!(s.samples.iter().all(|&v| v == 0));
        assert_eq!(s.samples.len(), RenderOptions::default().samples_for(span));
    }

    #[test]
    fn bad_settings_are_named() {
        let span = TimeSpan {
            start: 0.0,
            end: 1.0,
        };
        let mut opts = RenderOptions::default();
        opts.ring.hz = 30_000.0;
        assert!(matches!(
            render(&[], span, &opts),
            Err(RenderError::RingAboveNyquist { nyquist, .. }) if nyquist == 22_050.0
        ));
        let opts = RenderOptions {
            speed: 0.0,
            ..RenderOptions::default()
        };
        assert!(matches!(
            render(&[], span, &opts),
            Err(RenderError::Setting { name: "speed", .. })
        ));
        let opts = RenderOptions {
            speed: 1e-4,
            ..RenderOptions::default()
        };
        assert!(matches!(
            render(&[], span, &opts),
            Err(RenderError::TooLong { .. })
        ));
    }

    #[test]
    fn compression_laws() {
        assert_eq!(Compression::Sqrt.amplitude(9.0), 3.0);
        assert!((Compression::Log.amplitude(std::f64::consts::E - 1.0) - 1.0).abs() < 1e-15);
        assert_eq!(Compression::Log.amplitude(-1.0), 0.0);
    }
}
