//! Progress of a run in simulated time: a bar on a terminal, a line per tenth otherwise.

use indicatif::{ProgressBar, ProgressStyle as BarStyle};

use super::ProgressStyle;

/// Reports simulated time against the end time.
pub struct Progress {
    style: ProgressStyle,
    t_end: f64,
    bar: Option<ProgressBar>,
    next_line: u32,
}

/// Resolution of the bar (steps per run).
const BAR_STEPS: u64 = 1000;

impl Progress {
    /// Starts reporting for a run to `t_end`.
    pub fn new(style: ProgressStyle, t_end: f64) -> Progress {
        let bar = (style == ProgressStyle::Bar).then(|| {
            let bar = ProgressBar::new(BAR_STEPS);
            let template = "{elapsed_precise} [{bar:40}] {percent:>3}% {msg} (eta {eta})";
            if let Ok(s) = BarStyle::with_template(template) {
                bar.set_style(s.progress_chars("=> "));
            }
            bar
        });
        Progress {
            style,
            t_end,
            bar,
            next_line: 1,
        }
    }

    /// Whether it shows anything (a quiet run's progress is not worth a thread).
    pub fn shows(&self) -> bool {
        self.style != ProgressStyle::Quiet
    }

    /// The simulation reached `t`.
    pub fn update(&mut self, t: f64) {
        let fraction = (t / self.t_end).clamp(0.0, 1.0);
        match self.style {
            ProgressStyle::Bar => {
                if let Some(bar) = &self.bar {
                    let pos = (fraction * BAR_STEPS as f64) as u64;
                    if pos != bar.position() {
                        bar.set_position(pos);
                        bar.set_message(format!("t = {t:.2} s"));
                    }
                }
            }
            ProgressStyle::Lines => {
                while self.next_line <= 10 && fraction >= f64::from(self.next_line) / 10.0 {
                    eprintln!(
                        "t = {t:.3} s of {} s ({}%)",
                        self.t_end,
                        self.next_line * 10
                    );
                    self.next_line += 1;
                }
            }
            ProgressStyle::Quiet => {}
        }
    }

    /// The run ended.
    pub fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}
