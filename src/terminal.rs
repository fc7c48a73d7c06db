//! The progress bars of the command line, drawn on a terminal (the library says what they
//! show, [`eulerdisk::Bars`]; this program draws them).

use eulerdisk::{Bar, Bars, Counting};
use indicatif::{ProgressBar, ProgressStyle};

/// The command line's bars.
#[derive(Debug)]
pub struct TerminalBars;

/// The one value of [`TerminalBars`], for `ProgressStyle::Bar`.
pub static TERMINAL_BARS: TerminalBars = TerminalBars;

impl Bars for TerminalBars {
    fn start(&self, length: u64, what: Counting) -> Box<dyn Bar> {
        let bar = ProgressBar::new(length);
        let template = match what {
            Counting::SimulatedTime => {
                "{elapsed_precise} [{bar:40}] {percent:>3}% {msg} (eta {eta})"
            }
            Counting::Runs => "{elapsed_precise} [{bar:40}] {pos}/{len} runs, {msg} (eta {eta})",
        };
        if let Ok(style) = ProgressStyle::with_template(template) {
            bar.set_style(style.progress_chars("=> "));
        }
        Box::new(TerminalBar(bar))
    }
}

/// One bar on the terminal.
struct TerminalBar(ProgressBar);

impl Bar for TerminalBar {
    fn show(&self, position: u64, message: &str) {
        self.0.set_position(position);
        self.0.set_message(message.to_string());
    }

    fn println(&self, line: &str) {
        self.0.println(line);
    }

    fn finish(&self) {
        self.0.finish_and_clear();
    }
}
