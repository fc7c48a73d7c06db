//! A million samples of a model read at run time: the heavy top
//! (`model-macros/examples/heavy_top.dsl`) for 1 s, DOP853 at rtol 1e-8, atol 1e-10, recorded
//! at 10⁶ + 1 given times, each read off its step's dense output with the outputs evaluated
//! there. The solve alone, in process (no file written): what SciPy's `solve_ivp` with the same
//! `t_eval` is compared with (`scipy_compare.py` beside this file times SciPy and the whole
//! `model solve` process).
//!
//! ```text
//! cargo bench -p model-interpreted --bench dense_samples [-- --quick]
//! ```

use common::{Args, Clock};
use model_interpreted::{solve, ModelFile, SolveRequest};

#[path = "../../../equations/benches/common/mod.rs"]
#[allow(dead_code)]
mod common;

fn main() {
    let Args { quick, .. } = Args::parse();
    let repeats = if quick { 3 } else { 7 };
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let path = format!("{root}/model-macros/examples/heavy_top.dsl");
    let file = ModelFile::read(std::path::Path::new(&path)).unwrap();
    let model = file.model(None).unwrap();
    let count = 1_000_000;
    let mut request = SolveRequest::new(1.0);
    request.times = Some((0..=count).map(|k| k as f64 / count as f64).collect());
    let mut seconds = Vec::new();
    let mut rows = 0;
    for _ in 0..repeats {
        let clock = Clock::start();
        let solution = solve(model, &request).unwrap();
        seconds.push(clock.seconds());
        rows = solution.len();
        assert_eq!(rows, count + 1);
    }
    seconds.sort_by(f64::total_cmp);
    println!(
        "heavy top, 1 s, {rows} samples: {:.3} s (median of {repeats}, {}; min {:.3} s)",
        seconds[repeats / 2],
        Clock::kind(),
        seconds[0]
    );
}
