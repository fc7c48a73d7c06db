//! An observer that keeps everything a run reports, to compare two runs output for output.

use model_runtime::Const;
use model_runtime::{Observer, Sample, StepView, TransitionRecord};

/// Every step `(t0, t1, y0, y1)`, sample `(t, y)` and transition record of a run, in order.
pub struct RunLog<const N: usize, Md, G, Nt> {
    /// The steps as reported (an event that ends a segment cuts its step).
    pub steps: Vec<(f64, f64, [f64; N], [f64; N])>,
    /// The samples.
    pub samples: Vec<(f64, [f64; N])>,
    /// The transitions and passes.
    pub records: Vec<TransitionRecord<Const<N>, Md, G, Nt>>,
}

impl<const N: usize, Md, G, Nt> RunLog<N, Md, G, Nt> {
    /// An empty log.
    pub fn new() -> Self {
        RunLog {
            steps: Vec::new(),
            samples: Vec::new(),
            records: Vec::new(),
        }
    }
}

impl<const N: usize, Md, G, Nt> Observer<Const<N>, Md, G, Nt> for RunLog<N, Md, G, Nt> {
    fn on_step(&mut self, s: &StepView<'_, Const<N>, Md>) -> model_runtime::Observed {
        self.steps.push((s.t0, s.t1, *s.y0, *s.y1));
        Ok(())
    }
    fn on_sample(&mut self, s: &Sample<'_, Const<N>, Md>) -> model_runtime::Observed {
        self.samples.push((s.t, *s.y));
        Ok(())
    }
    fn on_transition(
        &mut self,
        r: TransitionRecord<Const<N>, Md, G, Nt>,
    ) -> model_runtime::Observed {
        self.records.push(r);
        Ok(())
    }
}
