//! The disk's own models at extreme states: the generated Box 1 and Box 3 models (both slip
//! charts, and their pruned variants) and the hand-written reference of `equations`.
//!
//! An input is a list of `name = value` lines, the disk's parameters, `t` and the states of
//! every model by name (`theta`, `v_C`, `u_X`, ...); each model reads its own names. Inputs
//! are the seeds of `fuzz/corpus/models/` (physical states: the paper's start, upright, flat,
//! sliding slowly) with one to six values replaced by zeros, signed zeros, subnormals, ±1e308,
//! infinities, NaN, θ at 0, π or one ulp from π, spins up to 1e300 rad/s, slips down to the
//! smallest subnormal, or scaled by a power of ten. Parameters the disk's validation refuses
//! are a clear error, as in a run. Every right-hand side, Jacobian and output evaluation must
//! give finite numbers or an error: an `Ok` carrying a NaN or an infinity would flow on
//! through a run unnoticed, so it is a finding, as is a panic or a hang.

use std::collections::BTreeMap;
use std::f64::consts::PI;

use equations::models::{rolling, sliding, sliding_cartesian};
use equations::reference::{RollingReference, SlidingCartesianReference, SlidingPolarReference};
use equations::DiskParams;
use model_runtime::{EvalError, WithOutputs};

use crate::rng::Rng;
use crate::supervisor::{Corpus, Target};

/// The models target.
#[derive(Debug)]
pub struct Models {
    corpus: Corpus,
}

impl Models {
    /// The target, seeded from `fuzz/corpus/models/`.
    pub const fn new() -> Models {
        Models {
            corpus: Corpus::new(&["fuzz/corpus/models"]),
        }
    }
}

impl Default for Models {
    fn default() -> Self {
        Models::new()
    }
}

/// An input's numbers by name, in the order written.
type Values = BTreeMap<String, f64>;

/// Reads `name = value` lines; other lines are ignored.
pub fn read(text: &str) -> Values {
    text.lines()
        .filter_map(|line| {
            let (name, value) = line.split_once('=')?;
            Some((name.trim().to_string(), value.trim().parse().ok()?))
        })
        .collect()
}

fn write(values: &Values) -> String {
    values
        .iter()
        .map(|(k, v)| format!("{k} = {v:?}\n"))
        .collect()
}

/// Values that break careless arithmetic, for any slot.
const EXTREMES: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    5e-324,
    -5e-324,
    f64::MIN_POSITIVE,
    1e-308,
    1e308,
    -1e308,
    f64::MAX,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NAN,
    1e16,
];

/// Where the disk's own singularities lie.
const THETAS: &[f64] = &[
    0.0,
    1e-300,
    1e-8,
    PI,
    f64::from_bits(PI.to_bits() - 1),
    f64::from_bits(PI.to_bits() + 1),
    PI - 1e-8,
    PI / 2.0,
    2.0 * PI,
    -PI / 2.0,
];

/// Huge spins and vanishing slips.
const SPINS: &[f64] = &[1e8, -1e8, 1e150, -1e150, 1e300, -1e300];
const SLIPS: &[f64] = &[0.0, -0.0, 5e-324, 1e-300, 1e-160, 1e-30, -1e-30];

fn mutate(values: &mut Values, rng: &mut Rng) {
    let names: Vec<String> = values.keys().cloned().collect();
    let Some(name) = names.get(rng.below(names.len())) else {
        return;
    };
    let old = values[name];
    let new = match rng.below(6) {
        0 | 1 => *rng.pick(EXTREMES),
        2 if name == "theta" => *rng.pick(THETAS),
        2 if name.starts_with("Omega") || name.starts_with("V_") => *rng.pick(SPINS),
        2 => *rng.pick(SLIPS),
        3 => old * 10f64.powi(rng.below(641) as i32 - 320),
        4 => -old,
        _ => f64::from_bits(
            old.to_bits()
                .wrapping_add(rng.below(5) as u64)
                .wrapping_sub(2),
        ),
    };
    values.insert(name.clone(), new);
}

impl Target for Models {
    fn name(&self) -> &'static str {
        "models"
    }

    fn extension(&self) -> &'static str {
        "txt"
    }

    fn seeds(&self) -> &[String] {
        self.corpus.texts()
    }

    fn input(&self, rng: &mut Rng) -> String {
        let mut values = read(rng.pick(self.corpus.texts()).as_str());
        for _ in 0..1 + rng.below(6) {
            mutate(&mut values, rng);
        }
        write(&values)
    }

    fn check(&self, text: &str) -> Result<(), String> {
        let values = read(text);
        let number = |name: &str, default: f64| values.get(name).copied().unwrap_or(default);
        let paper = DiskParams::paper();
        let params = DiskParams {
            m: number("m", paper.m),
            a: number("a", paper.a),
            g: number("g", paper.g),
            mu_d: number("mu_d", paper.mu_d),
            mu_st: number("mu_st", paper.mu_st),
            mu_a: number("mu_a", paper.mu_a),
            w_z: number("w_z", paper.w_z),
        };
        let Ok(params) = params.validated() else {
            return Ok(()); // a clear error, as a scene with these parameters gets
        };
        let t = number("t", 0.0);
        let p = params.to_array();
        let at = Evaluation { t, values: &values };
        at.model(&rolling::Model::new(p))?;
        at.model(&sliding::Model::new(p))?;
        at.model(&sliding_cartesian::Model::new(p))?;
        if params.mu_a == 0.0 && params.w_z == 0.0 {
            at.model(&rolling::pruned::Model::new(by_name(
                &rolling::pruned::INFO,
                &values,
            )))?;
            at.model(&sliding::pruned::Model::new(by_name(
                &sliding::pruned::INFO,
                &values,
            )))?;
            let cartesian = &sliding_cartesian::pruned::INFO;
            at.model(&sliding_cartesian::pruned::Model::new(by_name(
                cartesian, &values,
            )))?;
        }
        let refused = |e| format!("the reference refused valid parameters: {e}");
        at.model(&RollingReference::new(params).map_err(refused)?)?;
        at.model(&SlidingPolarReference::new(params).map_err(refused)?)?;
        at.model(&SlidingCartesianReference::new(params).map_err(refused)?)?;
        Ok(())
    }
}

/// A model's parameter array by its parameter names (the paper's value where the input has
/// none).
fn by_name<const P: usize>(info: &model_runtime::ModelInfo, values: &Values) -> [f64; P] {
    let paper = DiskParams::paper().to_array();
    std::array::from_fn(|i| {
        let name = &info.param_names[i];
        let k = DiskParams::NAMES.iter().position(|&n| n == name);
        values
            .get(name)
            .copied()
            .or(k.map(|k| paper[k]))
            .unwrap_or(0.0)
    })
}

/// One state of every model, read by the model's own names.
struct Evaluation<'a> {
    t: f64,
    values: &'a Values,
}

impl Evaluation<'_> {
    /// The right-hand side, the Jacobian and the outputs of `model`: each an error or finite.
    fn model<const N: usize, const K: usize>(
        &self,
        model: &impl WithOutputs<N, K>,
    ) -> Result<(), String> {
        let info = model.info();
        let y: [f64; N] = std::array::from_fn(|i| {
            self.values
                .get(&info.state_names[i])
                .copied()
                .unwrap_or(0.0)
        });
        let name = &info.name;
        let mut dy = [0.0; N];
        if let Some(wrong) = finite(model.rhs(self.t, &y, &mut dy), &dy) {
            return Err(format!(
                "{name}: rhs is Ok with der({}) = {wrong}",
                &info.state_names[wrong_at(&dy)]
            ));
        }
        let mut jac = [[0.0; N]; N];
        let jacobian = model.jacobian(self.t, &y, &mut jac);
        if let Some(wrong) = finite(jacobian, jac.as_flattened()) {
            return Err(format!("{name}: jacobian is Ok with an entry {wrong}"));
        }
        if dy.iter().all(|v| v.is_finite()) {
            let mut out = [0.0; K];
            if let Some(wrong) = finite(model.outputs(self.t, &y, &dy, &mut out), &out) {
                let at = &info.output_names[wrong_at(&out)];
                return Err(format!("{name}: outputs are Ok with {at} = {wrong}"));
            }
        }
        Ok(())
    }
}

/// The first non-finite number of `numbers` when `result` is `Ok`.
fn finite(result: Result<(), EvalError>, numbers: &[f64]) -> Option<f64> {
    result.ok()?;
    numbers.iter().copied().find(|v| !v.is_finite())
}

fn wrong_at(numbers: &[f64]) -> usize {
    numbers.iter().position(|v| !v.is_finite()).unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_input_reads_back_as_written_special_values_included() {
        let values: Values = [
            ("theta", PI),
            ("v_C", 5e-324),
            ("a", -0.0),
            ("Omega_z", f64::NAN),
        ]
        .into_iter()
        .chain([
            ("psi", f64::NEG_INFINITY),
            ("m", f64::from_bits(PI.to_bits() + 1)),
        ])
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        let again = read(&write(&values));
        assert_eq!(again.len(), values.len());
        for (k, v) in &values {
            assert_eq!(again[k].to_bits(), v.to_bits(), "{k}");
        }
    }

    #[test]
    fn an_ok_carrying_a_non_finite_number_is_caught_and_an_error_is_not() {
        assert_eq!(finite(Ok(()), &[1.0, 2.0]), None);
        assert!(finite(Ok(()), &[1.0, f64::NAN]).is_some_and(f64::is_nan));
        assert_eq!(finite(Ok(()), &[f64::INFINITY]), Some(f64::INFINITY));
        let refused = EvalError::NonFinite {
            model: "m".into(),
            quantity: "der(x)".into(),
            value: f64::NAN,
        };
        assert_eq!(finite(Err(refused), &[f64::NAN]), None);
    }

    #[test]
    fn the_paper_start_evaluates_in_every_model() {
        let seed =
            "m = 0.4387\na = 0.03755\ntheta = 0.5707963267948966\nZ = 0.0203\nOmega_x = 1.0\n";
        Models::new().check(seed).unwrap();
    }
}
