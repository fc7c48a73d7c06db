//! What the benches share: the clock they read and where they write.
//!
//! The machine the numbers come from is shared and busy, so wall-clock time measures the
//! neighbours as much as the code. The benches read the CPU time of their own thread instead
//! (`CLOCK_THREAD_CPUTIME_ID`), and fall back to the wall clock elsewhere;
//! which one was used is printed with every table.

use std::path::PathBuf;
use std::time::Instant;

/// A clock for one measurement.
pub struct Clock {
    wall: Instant,
    cpu: Option<f64>,
}

/// CPU time this thread has run (s), if the platform tells.
fn thread_cpu_seconds() -> Option<f64> {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec for the duration of the call.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    (rc == 0).then_some(ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9)
}

impl Clock {
    /// Starts the clock.
    pub fn start() -> Self {
        Clock {
            cpu: thread_cpu_seconds(),
            wall: Instant::now(),
        }
    }

    /// Seconds since the start: CPU time of this thread where available, else wall time.
    pub fn seconds(&self) -> f64 {
        match (self.cpu, thread_cpu_seconds()) {
            (Some(a), Some(b)) => b - a,
            _ => self.wall.elapsed().as_secs_f64(),
        }
    }

    /// Which clock [`Clock::seconds`] reads.
    pub fn kind() -> &'static str {
        if thread_cpu_seconds().is_some() {
            "CPU time of the benchmark thread"
        } else {
            "wall-clock time"
        }
    }
}

/// Command-line switches every bench accepts: `--quick` and `--out DIR`.
pub struct Args {
    /// A short run (under a minute).
    pub quick: bool,
    /// Where tables and figures go (default: the workspace's `target/bench`).
    pub out: PathBuf,
}

impl Args {
    /// Reads the process arguments (cargo's own `--bench` flag is ignored).
    pub fn parse() -> Self {
        let args: Vec<String> = std::env::args().skip(1).collect();
        let quick = args.iter().any(|a| a == "--quick");
        let out = args
            .iter()
            .position(|a| a == "--out")
            .and_then(|i| args.get(i + 1))
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target/bench"));
        Args { quick, out }
    }
}
