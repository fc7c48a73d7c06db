//! The work bound of a scene: the runtime's [`WorkBound`], set by the scene's
//! `solver.max_steps_per_s` ([`WORK_BOUND_KEY`]); a run over it fails with
//! [`crate::SimError::WorkBound`].
//!
//! Why the disk needs it: a valid scene can need steps so short that it would run for hours
//! without ever failing. A disk of radius 1e-12 m started near θ = π takes about 2e8 steps per
//! simulated second (its time scale `sqrt(a/g)` is 3e-7 s). The paper's 100 s scene takes
//! about 3e3 steps per simulated second (at most 4150 in any one of its seconds), so the
//! default (`WorkBound::DEFAULT`, 1e6) leaves it a margin of 240.

pub use model_runtime::{WorkBound, WorkExceeded};

/// The scene key of the work bound.
pub const WORK_BOUND_KEY: &str = "solver.max_steps_per_s";

/// The sentence of a run over its bound, in the scene's words.
pub(crate) fn describe(over: &WorkExceeded) -> String {
    over.describe(WORK_BOUND_KEY, " s")
}

#[cfg(test)]
mod tests {
    use super::*;
    use model_runtime::WorkMeter;

    #[test]
    fn the_sentence_names_the_scene_key_and_seconds() {
        let mut meter = WorkMeter::new(WorkBound { steps_per_s: 10.0 }, 0.0);
        let over = (0..10)
            .find_map(|k| meter.step(k as f64 * 1e-3, (k + 1) as f64 * 1e-3))
            .expect("the second step is over 10 × (0.001 + 0.1) = 1.01 steps");
        let message = describe(&over);
        assert!(
            message.contains("raise `solver.max_steps_per_s`"),
            "{message}"
        );
        assert!(message.contains("of simulated time"), "{message}");
        assert!(message.contains(" s long"), "{message}");
    }
}
