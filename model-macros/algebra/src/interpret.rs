//! A compiled model run by the interpreter, as a whole: its derivatives, its outputs and a
//! finite-difference check of its Jacobian, by the model's state and parameter order.
//!
//! This is what lets a model be evaluated without compiling Rust (a tool reading a DSL file)
//! and what tests compare the symbolic Jacobian with.

use crate::eval::{EvalFailure, Inputs};
use crate::flat::{FlatError, FlatProgram, Shape, Sink};
use crate::program::CompiledModel;

/// A model's three programs laid out in slots ([`FlatProgram`]), for a given number of
/// parameters (a switched model's modes read its discrete values after them).
#[derive(Clone, Debug, PartialEq)]
pub struct FlatModel {
    /// `dy = f(t, y, p)` into `dy`.
    pub rhs: FlatProgram,
    /// The Jacobian, row-major into `n²` values.
    pub jacobian: FlatProgram,
    /// The outputs, given `dy`.
    pub outputs: FlatProgram,
}

impl FlatModel {
    /// `model`'s programs, reading `params` parameters.
    pub fn new(model: &CompiledModel, params: usize) -> Result<Self, FlatError> {
        let n = model.states.len();
        let shape = Shape {
            states: n,
            params,
            ders: 0,
        };
        Ok(FlatModel {
            rhs: FlatProgram::new(&model.rhs, shape, Sink::Ders(n))?,
            jacobian: FlatProgram::new(&model.jacobian, shape, Sink::Jacobian(n))?,
            outputs: FlatProgram::new(
                &model.outputs_program,
                Shape { ders: n, ..shape },
                Sink::Outputs(model.outputs.len()),
            )?,
        })
    }
}

impl CompiledModel {
    /// `dy = f(t, y, p)`, interpreted.
    pub fn derivatives(
        &self,
        t: f64,
        states: &[f64],
        params: &[f64],
    ) -> Result<Vec<f64>, EvalFailure> {
        let inputs = Inputs {
            t,
            states,
            params,
            ders: &[],
        };
        Ok(self.rhs.eval(&inputs)?.ders(self.states.len()))
    }

    /// The outputs at `(t, y)` with the derivatives `dy` there, interpreted.
    pub fn outputs_at(
        &self,
        t: f64,
        states: &[f64],
        ders: &[f64],
        params: &[f64],
    ) -> Result<Vec<f64>, EvalFailure> {
        let inputs = Inputs {
            t,
            states,
            params,
            ders,
        };
        Ok(self
            .outputs_program
            .eval(&inputs)?
            .outputs(self.outputs.len()))
    }

    /// Central differences of the interpreted right-hand side at `t = 0`, with steps
    /// `relative_step · max(|y_j|, 1)`: `jac[i][j] ≈ ∂f_i/∂y_j`.
    pub fn finite_difference_jacobian(
        &self,
        states: &[f64],
        params: &[f64],
        relative_step: f64,
    ) -> Result<Vec<Vec<f64>>, EvalFailure> {
        let n = states.len();
        let mut jac = vec![vec![0.0; n]; n];
        for j in 0..n {
            let h = relative_step * states[j].abs().max(1.0);
            let mut shifted = states.to_vec();
            shifted[j] += h;
            let plus = self.derivatives(0.0, &shifted, params)?;
            shifted[j] -= 2.0 * h;
            let minus = self.derivatives(0.0, &shifted, params)?;
            for i in 0..n {
                jac[i][j] = (plus[i] - minus[i]) / (2.0 * h);
            }
        }
        Ok(jac)
    }
}
