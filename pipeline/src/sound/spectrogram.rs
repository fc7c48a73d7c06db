//! The rendered sound's spectrum over time (short-time Fourier transform).
//!
//! The figure should show what an ear hears: the ring's pitch as a band, and the knocks as
//! vertical stripes that crowd together as the run goes on. Frames are Hann-windowed, so a
//! tone between two bins leaks into its neighbours only slightly, and power is in dB relative
//! to the loudest cell, so the picture does not depend on the sound's normalisation.

use rustfft::num_complex::Complex;
use rustfft::FftPlannerScalar;

/// Frame length and step of the transform.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StftSettings {
    /// Samples per frame (a power of two is fastest).
    pub frame: usize,
    /// Samples between the starts of consecutive frames.
    pub hop: usize,
}

impl Default for StftSettings {
    /// 1024-sample frames (23 ms, 43 Hz bins at 44.1 kHz) every 128 samples (2.9 ms):
    /// short enough to separate knocks 42 ms apart.
    fn default() -> Self {
        StftSettings {
            frame: 1024,
            hop: 128,
        }
    }
}

/// Why a spectrogram cannot be computed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SpectrogramError {
    /// Frame or hop is zero.
    #[error("spectrogram frame ({frame}) and hop ({hop}) must be positive")]
    EmptyFrame {
        /// Frame length.
        frame: usize,
        /// Hop.
        hop: usize,
    },
    /// The signal is shorter than one frame.
    #[error("the signal has {samples} samples, fewer than one frame of {frame}")]
    TooShort {
        /// Samples in the signal.
        samples: usize,
        /// Frame length.
        frame: usize,
    },
}

/// Power per frequency bin per frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrogram {
    /// Samples per second of the signal.
    pub sample_rate: f64,
    /// The transform's settings.
    pub settings: StftSettings,
    /// `power_db[frame][bin]`, dB relative to the largest cell (≤ 0, floored at
    /// [`FLOOR_DB`]).
    pub power_db: Vec<Vec<f32>>,
}

/// The quietest level kept (dB below the largest cell).
pub const FLOOR_DB: f32 = -120.0;

impl Spectrogram {
    /// Width of one frequency bin (Hz).
    pub fn bin_hz(&self) -> f64 {
        self.sample_rate / self.settings.frame as f64
    }

    /// Number of frequency bins (`frame/2 + 1`, from 0 Hz to Nyquist).
    pub fn bins(&self) -> usize {
        self.settings.frame / 2 + 1
    }

    /// Time of a frame's centre, from the signal's start (s).
    pub fn frame_time(&self, frame: usize) -> f64 {
        (frame * self.settings.hop) as f64 / self.sample_rate
            + 0.5 * self.settings.frame as f64 / self.sample_rate
    }

    /// The loudest bin of a frame.
    pub fn peak_bin(&self, frame: usize) -> Option<usize> {
        let row = self.power_db.get(frame)?;
        (0..row.len()).max_by(|&a, &b| row[a].total_cmp(&row[b]))
    }
}

/// The spectrogram of `signal` sampled at `sample_rate`.
pub fn spectrogram(
    signal: &[f64],
    sample_rate: f64,
    settings: StftSettings,
) -> Result<Spectrogram, SpectrogramError> {
    let StftSettings { frame, hop } = settings;
    if frame == 0 || hop == 0 {
        return Err(SpectrogramError::EmptyFrame { frame, hop });
    }
    if signal.len() < frame {
        return Err(SpectrogramError::TooShort {
            samples: signal.len(),
            frame,
        });
    }
    // The scalar planner: a frame of real samples goes through the complex transform (half its
    // output is the mirror of the other half). The SIMD planners would transform faster, but
    // the transform is a small part of rendering the sound, and their code, compiled into this
    // crate for every algorithm they may choose, was a fifth of the library's compile.
    let fft = FftPlannerScalar::<f64>::new().plan_fft_forward(frame);
    let window: Vec<f64> = (0..frame)
        .map(|i| 0.5 - 0.5 * (std::f64::consts::TAU * i as f64 / frame as f64).cos())
        .collect();
    let mut buffer = vec![Complex::default(); frame];
    let mut scratch = vec![Complex::default(); fft.get_inplace_scratch_len()];
    let bins = frame / 2 + 1;
    let frames = (signal.len() - frame) / hop + 1;
    let mut power = Vec::with_capacity(frames);
    let mut largest = 0.0f64;
    for f in 0..frames {
        let chunk = &signal[f * hop..f * hop + frame];
        for ((x, s), w) in buffer.iter_mut().zip(chunk).zip(&window) {
            *x = Complex::new(s * w, 0.0);
        }
        fft.process_with_scratch(&mut buffer, &mut scratch);
        let row: Vec<f64> = buffer[..bins].iter().map(|c| c.norm_sqr()).collect();
        largest = row.iter().fold(largest, |m, &p| m.max(p));
        power.push(row);
    }
    let power_db = power
        .into_iter()
        .map(|row| {
            row.into_iter()
                .map(|p| {
                    if largest > 0.0 && p > 0.0 {
                        ((10.0 * (p / largest).log10()) as f32).max(FLOOR_DB)
                    } else {
                        FLOOR_DB
                    }
                })
                .collect()
        })
        .collect();
    Ok(Spectrogram {
        sample_rate,
        settings,
        power_db,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_times_and_bins() {
        let s = spectrogram(
            &vec![0.0; 5000],
            1000.0,
            StftSettings {
                frame: 1000,
                hop: 500,
            },
        )
        .unwrap();
        assert_eq!(s.power_db.len(), 9);
        assert_eq!(s.bins(), 501);
        assert_eq!(s.bin_hz(), 1.0);
        assert_eq!(s.frame_time(0), 0.5);
        assert_eq!(s.frame_time(2), 1.5);
        // Silence is the floor everywhere, not NaN.
        assert!(s.power_db.iter().flatten().all(|&p| p == FLOOR_DB));
    }

    /// Each frame's power is the windowed frame's discrete Fourier transform, summed here
    /// term by term: a tone between bins and a click, at an odd frame length (no radix-2 path).
    #[test]
    fn the_power_is_the_windowed_frames_transform() {
        let (rate, frame, hop) = (1000.0, 90, 40);
        let signal: Vec<f64> = (0..400)
            .map(|i| {
                let t = i as f64 / rate;
                (std::f64::consts::TAU * 123.4 * t).sin() + if i == 217 { 3.0 } else { 0.0 }
            })
            .collect();
        let s = spectrogram(&signal, rate, StftSettings { frame, hop }).unwrap();
        let window = |i: usize| 0.5 - 0.5 * (std::f64::consts::TAU * i as f64 / frame as f64).cos();
        let power: Vec<Vec<f64>> = (0..s.power_db.len())
            .map(|f| {
                (0..frame / 2 + 1)
                    .map(|k| {
                        let (re, im) = (0..frame).fold((0.0, 0.0), |(re, im), i| {
                            let x = signal[f * hop + i] * window(i);
                            let a = -std::f64::consts::TAU * (k * i) as f64 / frame as f64;
                            (re + x * a.cos(), im + x * a.sin())
                        });
                        re * re + im * im
                    })
                    .collect()
            })
            .collect();
        let largest = power.iter().flatten().fold(0.0f64, |m, &p| m.max(p));
        for (row, direct) in s.power_db.iter().zip(&power) {
            assert_eq!(row.len(), direct.len());
            for (&db, &p) in row.iter().zip(direct) {
                let expected = ((10.0 * (p / largest).log10()) as f32).max(FLOOR_DB);
                assert!(
                    (db - expected).abs() < 1e-3,
                    "{db} dB against {expected} dB"
                );
            }
        }
        // The tone's bin: 123.4 Hz at 1000/90 Hz per bin.
        assert_eq!(s.peak_bin(0), Some(11));
    }

    #[test]
    fn bad_settings_are_named() {
        assert_eq!(
            spectrogram(&[0.0; 10], 1.0, StftSettings { frame: 16, hop: 4 }),
            Err(SpectrogramError::TooShort {
                samples: 10,
                frame: 16
            })
        );
        assert_eq!(
            spectrogram(&[0.0; 10], 1.0, StftSettings { frame: 0, hop: 4 }),
            Err(SpectrogramError::EmptyFrame { frame: 0, hop: 4 })
        );
    }
}
