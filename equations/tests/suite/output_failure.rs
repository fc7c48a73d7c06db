//! A model that fails only where the run's output is evaluated (a sample) ends the run there:
//! the failure is typed ([`SimError::Output`]), dated at that sample, and comes with the work
//! done and the last state reached, in physical and in regularised time alike. The run does
//! not go on past it (before the failure travelled through the driver, the run went on to its
//! end time and reported the failure afterwards, with the whole run's work).

use equations::{
    simulate, DiskConfig, DiskModels, DiskParams, DiskRecorder, GeneratedModels, InitialState,
    SimError, SlipChart, TimeVariable,
};
use model_runtime::{EvalError, Model, ModelInfo};

/// `inner`, refusing to evaluate at exactly `t` (a sample's time, which no integration stage
/// meets: the stages and the located events fall between the grid's points).
struct RefusesAt<M> {
    inner: M,
    t: f64,
}

impl<M: Model<12>> Model<12> for RefusesAt<M> {
    fn info(&self) -> &'static ModelInfo {
        self.inner.info()
    }

    fn rhs(&self, t: f64, y: &[f64; 12], dy: &mut [f64; 12]) -> Result<(), EvalError> {
        if t == self.t {
            return Err(EvalError::non_finite("refuses", "t", t));
        }
        self.inner.rhs(t, y, dy)
    }

    fn jacobian(&self, t: f64, y: &[f64; 12], jac: &mut [[f64; 12]; 12]) -> Result<(), EvalError> {
        self.inner.jacobian(t, y, jac)
    }
}

/// The paper's models, both refusing `t`.
fn refusing(params: DiskParams, t: f64) -> DiskModels<impl Model<12>, impl Model<12>> {
    let models = GeneratedModels::generated(params, SlipChart::Cartesian).unwrap();
    DiskModels {
        params: models.params,
        rolling: RefusesAt {
            inner: models.rolling,
            t,
        },
        sliding: RefusesAt {
            inner: models.sliding,
            t,
        },
        chart: models.chart,
    }
}

#[test]
fn a_sample_the_models_refuse_ends_the_run_there() {
    let params = DiskParams::paper();
    let initial = InitialState::paper(&params);
    for time in [TimeVariable::Physical, TimeVariable::Regularised] {
        let config = DiskConfig {
            t_end: 1.0,
            time,
            sample_rate: Some(1000.0),
            ..DiskConfig::default()
        };
        let whole = GeneratedModels::generated(params, SlipChart::Cartesian).unwrap();
        let whole = simulate(&whole, &config, &initial, &mut ()).unwrap();
        let mut record = DiskRecorder::default();
        let failure = simulate(&refusing(params, 0.25), &config, &initial, &mut record)
            .expect_err("the sample at t = 0.25 cannot be evaluated");
        match &failure.error {
            SimError::Output { t, source, .. } => {
                assert_eq!(*t, 0.25, "{time:?}");
                assert!(
                    matches!(source, EvalError::NonFinite { quantity, .. } if quantity == "t"),
                    "{source:?}"
                );
            }
            other => panic!("{time:?}: expected the output's failure, got {other:?}"),
        }
        assert_eq!(failure.error.time(), Some(0.25));
        assert!(failure.to_string().contains("t = 0.25"), "{failure}");
        // Every sample before it was delivered, none at or after it.
        let times: Vec<f64> = record.samples.iter().map(|s| s.t).collect();
        assert_eq!(times.len(), 250, "{time:?}");
        assert_eq!(times.last(), Some(&0.249));
        // The work until then, a fraction of the whole run's, and where it got.
        let steps = failure.stats.steps;
        assert!(
            steps > 0 && steps < whole.stats.steps / 2,
            "{time:?}: {steps} steps of {}",
            whole.stats.steps
        );
        assert!(failure.stats.rhs_evals > 0);
        let last = failure.last.as_ref().expect("the last accepted step");
        assert!(
            last.t <= 0.25 && last.t > 0.2,
            "{time:?}: last state at {}",
            last.t
        );
    }
}
