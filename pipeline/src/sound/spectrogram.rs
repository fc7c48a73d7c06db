//! The rendered sound's spectrum over time (short-time Fourier transform).
//!
//! The figure should show what an ear hears: the ring's pitch as a band, and the knocks as
//! vertical stripes that crowd together as the run goes on. Frames are Hann-windowed, so a
//! tone between two bins leaks into its neighbours only slightly, and power is in dB relative
//! to the loudest cell, so the picture does not depend on the sound's normalisation.

use realfft::RealFftPlanner;

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
    /// The transform rejected its buffers (their lengths come from its own plan, so this
    /// would be a defect of the transform library).
    #[error("the Fourier transform failed: {message}")]
    Transform {
        /// The library's message.
        message: String,
    },
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
    let fft = RealFftPlanner::<f64>::new().plan_fft_forward(frame);
    let window: Vec<f64> = (0..frame)
        .map(|i| 0.5 - 0.5 * (std::f64::consts::TAU * i as f64 / frame as f64).cos())
        .collect();
    let mut input = fft.make_input_vec();
    let mut spectrum = fft.make_output_vec();
    let mut scratch = fft.make_scratch_vec();
    let frames = (signal.len() - frame) / hop + 1;
    let mut power = Vec::with_capacity(frames);
    let mut largest = 0.0f64;
    for f in 0..frames {
        let chunk = &signal[f * hop..f * hop + frame];
        for ((x, s), w) in input.iter_mut().zip(chunk).zip(&window) {
            *x = s * w;
        }
        fft.process_with_scratch(&mut input, &mut spectrum, &mut scratch)
            .map_err(|e| SpectrogramError::Transform {
                message: e.to_string(),
            })?;
        let row: Vec<f64> = spectrum.iter().map(|c| c.norm_sqr()).collect();
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
