//! Progress of a run in simulated time: a bar a front end draws, a line per tenth, or nothing.
//!
//! The library says what progress shows; it draws no bar itself, so that it links no terminal
//! crate (the Python package uses it too). A front end with a terminal gives its bars as a
//! [`Bars`] (the command line's are drawn with a terminal crate, in `src/terminal.rs`).

use std::fmt;

/// How a run, or a sweep, reports while it runs.
#[derive(Clone, Copy, Debug)]
pub enum ProgressStyle {
    /// A progress bar, drawn by the front end.
    Bar(&'static dyn Bars),
    /// A plain line on standard error every 10%.
    Lines,
    /// Nothing.
    Quiet,
}

impl ProgressStyle {
    /// Whether nothing is reported.
    pub fn is_quiet(self) -> bool {
        matches!(self, ProgressStyle::Quiet)
    }

    /// Whether progress goes out as lines.
    pub fn is_lines(self) -> bool {
        matches!(self, ProgressStyle::Lines)
    }

    /// A bar of `length` steps counting `what`, if this style draws bars.
    pub fn bar(self, length: u64, what: Counting) -> Option<Box<dyn Bar>> {
        match self {
            ProgressStyle::Bar(bars) => Some(bars.start(length, what)),
            ProgressStyle::Lines | ProgressStyle::Quiet => None,
        }
    }
}

/// What a bar counts, for the front end to label it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Counting {
    /// A run's simulated time, in steps of the end time (a percentage).
    SimulatedTime,
    /// A sweep's runs (`done/total runs`).
    Runs,
}

/// The progress bars of a front end (the command line's, on a terminal).
pub trait Bars: fmt::Debug + Sync {
    /// Starts a bar of `length` steps counting `what`.
    fn start(&self, length: u64, what: Counting) -> Box<dyn Bar>;
}

/// One progress bar, drawn while it lives.
pub trait Bar {
    /// Moves the bar to `position` of its length, with `message` beside it.
    fn show(&self, position: u64, message: &str);
    /// Prints `line` above the bar.
    fn println(&self, line: &str);
    /// Removes the bar.
    fn finish(&self);
}

/// Reports simulated time against the end time.
pub struct Progress {
    style: ProgressStyle,
    t_end: f64,
    bar: Option<Box<dyn Bar>>,
    position: u64,
    next_line: u32,
}

/// Resolution of the bar (steps per run).
const BAR_STEPS: u64 = 1000;

impl Progress {
    /// Starts reporting for a run to `t_end`.
    pub fn new(style: ProgressStyle, t_end: f64) -> Progress {
        Progress {
            style,
            t_end,
            bar: style.bar(BAR_STEPS, Counting::SimulatedTime),
            position: 0,
            next_line: 1,
        }
    }

    /// Whether it shows anything (a quiet run's progress is not worth a thread).
    pub fn shows(&self) -> bool {
        !self.style.is_quiet()
    }

    /// The simulation reached `t`.
    pub fn update(&mut self, t: f64) {
        let fraction = (t / self.t_end).clamp(0.0, 1.0);
        if let Some(bar) = &self.bar {
            let position = (fraction * BAR_STEPS as f64) as u64;
            if position != self.position {
                bar.show(position, &format!("t = {t:.2} s"));
                self.position = position;
            }
        } else if self.style.is_lines() {
            while self.next_line <= 10 && fraction >= f64::from(self.next_line) / 10.0 {
                eprintln!(
                    "t = {t:.3} s of {} s ({}%)",
                    self.t_end,
                    self.next_line * 10
                );
                self.next_line += 1;
            }
        }
    }

    /// The run ended.
    pub fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish();
        }
    }
}
