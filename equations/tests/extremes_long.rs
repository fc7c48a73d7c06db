//! A long horizon: the paper's scene (docs/physics.md §11, the paper's DP5 at rtol 1e-8, atol
//! 1e-10) run to `T_END` s or until it stops.
//!
//! Nothing of a run is kept unless the observer keeps it, so memory must not grow with the
//! horizon: the peak resident set (`VmHWM` of `/proc/self/status`) after the first 100 s and
//! at the end may differ only by allocator noise. This test is its own binary so that no
//! other test's allocations move that peak. The constraints are imposed only in differential
//! form and projected at every switch, so their drift must stay at the integration error
//! between switches, not grow with the horizon: the largest drift after 100 s must stay within
//! a small factor of the largest before.

// It measures the peak memory of its process, so it keeps a test binary of its own.
#[path = "suite/common/mod.rs"]
mod common;

use common::extreme::Watch;
use equations::DiskParams;
use equations::SlipChart;
use equations::{simulate, DiskObserver, DiskSample, GeneratedModels, TransitionRecord};
use equations::{DiskConfig, InitialState};

/// The horizon (s).
const T_END: f64 = 1000.0;
/// Where the first memory reading is taken (s).
const T_FIRST: f64 = 100.0;
/// Allowed growth of the peak resident set between the readings (kB).
const GROWTH_KB: u64 = 1024;

/// `VmHWM`, the peak resident set of this process (kB).
fn peak_rss_kb() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").expect("procfs");
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .expect("VmHWM in /proc/self/status")
}

/// A streaming watch that also reads the memory peak once the run passes `T_FIRST` and keeps
/// the drift before and after.
struct LongWatch {
    watch: Watch,
    peak_at_first: Option<u64>,
    drift_before: f64,
}

impl LongWatch {
    fn note(&mut self, s: &DiskSample) {
        if s.t < T_FIRST {
            self.drift_before = self.drift_before.max(s.residuals.max_abs());
        } else if self.peak_at_first.is_none() {
            self.peak_at_first = Some(peak_rss_kb());
        }
    }
}

impl DiskObserver for LongWatch {
    fn on_sample(&mut self, sample: &DiskSample) {
        self.note(sample);
        self.watch.on_sample(sample);
    }
    fn wants_steps(&self) -> bool {
        true
    }
    fn on_step(&mut self, sample: &DiskSample) {
        self.note(sample);
        self.watch.on_step(sample);
    }
    fn on_transition(&mut self, record: &TransitionRecord) {
        self.watch.on_transition(record);
    }
}

#[test]
fn the_paper_scene_runs_long_with_flat_memory_and_bounded_drift() {
    let p = DiskParams::paper();
    let models = GeneratedModels::generated(p, SlipChart::Cartesian).unwrap();
    let config = DiskConfig {
        t_end: T_END,
        sample_rate: Some(100.0),
        ..DiskConfig::paper()
    };
    let mut long = LongWatch {
        watch: Watch::streaming(),
        peak_at_first: None,
        drift_before: 0.0,
    };
    let result = simulate(&models, &config, &InitialState::paper(&p), &mut long);
    let peak_end = peak_rss_kb();
    let watch = &long.watch;
    println!(
        "result {:?}",
        result
            .as_ref()
            .map(|o| (o.stop, o.last.t, o.transitions, o.stats.steps))
    );
    println!(
        "peak RSS at {T_FIRST} s: {:?} kB, at the end: {peak_end} kB; drift before {T_FIRST} s {:.2e}, overall {:.2e}; θ in {:?}; {} observations",
        long.peak_at_first, long.drift_before, watch.max_drift, watch.theta_range, watch.seen
    );
    let out = result.unwrap();
    watch.assert_finite("long horizon");
    let first = long.peak_at_first.expect("the run passed 100 s");
    assert!(peak_end <= first + GROWTH_KB, "{first} kB → {peak_end} kB");
    assert!(
        watch.max_drift <= 10.0 * long.drift_before,
        "{:e}",
        watch.max_drift
    );
    assert!(out.last.t > T_FIRST);
}
