//! The latest steps a run keeps (`equations::hybrid::trailing`), sampled after the run on its
//! grid, give the samples the run delivered there, bit for bit, in physical and in regularised
//! time; and the ring holds no more steps than the grid has points in its span.

use equations::{
    simulate, DiskConfig, DiskObserver, DiskParams, DiskSample, GeneratedModels, InitialState,
    SlipChart, TimeVariable, Trailing,
};

/// Keeps every live sample, and the samples of the kept steps at the end.
struct Both {
    span: f64,
    live: Vec<DiskSample>,
    kept: Vec<DiskSample>,
    steps: usize,
    end: f64,
}

impl DiskObserver for Both {
    fn on_sample(&mut self, sample: &DiskSample) {
        self.live.push(*sample);
    }
    fn keeps_trailing(&self) -> Option<f64> {
        Some(self.span)
    }
    fn on_trailing(&mut self, trailing: &Trailing<'_>) {
        let (_, end) = trailing.span().unwrap();
        self.end = end;
        self.steps = trailing.steps();
        // The regularised clock may end an ulp past the end time: the grid from the half
        // second before the end time itself.
        self.kept = (trailing.grid(end.round() - self.span))
            .map(|t| trailing.sample(t).unwrap().unwrap())
            .collect();
        // Off the grid and outside the kept steps, nothing.
        assert!(trailing.sample(end + 1.0).is_none());
        assert!(trailing.sample(end - 2.0 * self.span).is_none());
    }
}

fn runs_alike(time: TimeVariable) {
    let p = DiskParams::paper();
    let models = GeneratedModels::generated(p, SlipChart::Cartesian).unwrap();
    let rate = 2000.0;
    let config = DiskConfig {
        t_end: 3.0,
        sample_rate: Some(rate),
        time,
        ..DiskConfig::default()
    };
    let mut both = Both {
        span: 0.5,
        live: Vec::new(),
        kept: Vec::new(),
        steps: 0,
        end: 0.0,
    };
    simulate(&models, &config, &InitialState::paper(&p), &mut both).unwrap();
    assert!((both.end - 3.0).abs() < 1e-12, "{time:?}: {}", both.end);
    let live: Vec<&DiskSample> = (both.live.iter())
        .filter(|s| s.t >= 3.0 - both.span)
        .collect();
    assert_eq!(live.len(), 1001, "{time:?}");
    assert_eq!(both.kept.len(), live.len(), "{time:?}");
    for (a, b) in both.kept.iter().zip(live) {
        assert_eq!(a.t.to_bits(), b.t.to_bits());
        assert_eq!(a.mode, b.mode);
        assert_eq!(
            a.state.y.map(f64::to_bits),
            b.state.y.map(f64::to_bits),
            "{}",
            a.t
        );
        assert_eq!(a.force.normal.to_bits(), b.force.normal.to_bits());
    }
    // One step per grid point at most, and a few at the ends of the span.
    assert!(
        both.steps <= (rate * both.span) as usize + 3,
        "{}",
        both.steps
    );
    assert!(both.steps > 10, "{}", both.steps);
}

#[test]
fn the_kept_steps_sample_as_the_run_did() {
    runs_alike(TimeVariable::Physical);
    runs_alike(TimeVariable::Regularised);
}
