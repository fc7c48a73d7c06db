//! Random implicit models `M(y) dy = f(y)` compiled end to end and compared with a numeric
//! solve of the same system evaluated from the user's trees; their Jacobians compared with
//! finite differences of the compiled right-hand side.

use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

use super::props::{ast, eval_ast, ill_conditioned};
use crate::eval::Inputs;
use crate::spec::{Ast, BinOp, EquationSpec, ModelSpec, Named, NodeId};
use crate::{compile, CompileOptions};

/// Three states `x, y, w` (the trees read `x`, `y` and the parameter `z`).
#[derive(Clone, Debug)]
pub(super) struct RandomModel {
    pub(super) n: usize,
    /// Row-major coefficients; the diagonal gets `+ 4` so that the matrix is usually regular.
    mass: Vec<Option<Ast>>,
    forcing: Vec<Ast>,
}

const STATES: [&str; 3] = ["x", "y", "w"];

pub(super) fn random_model() -> impl Strategy<Value = RandomModel> {
    (1usize..=3).prop_flat_map(|n| {
        (
            prop::collection::vec(prop::option::weighted(0.7, ast(false, false)), n * n),
            prop::collection::vec(ast(false, false), n),
        )
            .prop_map(move |(mass, forcing)| RandomModel { n, mass, forcing })
    })
}

fn bin(op: BinOp, a: Ast, b: Ast) -> Ast {
    Ast::Bin(NodeId(40), op, Box::new(a), Box::new(b))
}

fn coefficient(model: &RandomModel, i: usize, j: usize) -> Option<Ast> {
    let c = model.mass[i * model.n + j].clone();
    if i == j {
        let four = Ast::Num(NodeId(41), 4.0);
        Some(c.map_or(four.clone(), |c| bin(BinOp::Add, four, c)))
    } else {
        c
    }
}

pub(super) fn spec(model: &RandomModel) -> ModelSpec {
    let named = |name: &str| Named {
        name: name.into(),
        id: NodeId(42),
        value: (),
    };
    let equations = (0..model.n)
        .map(|i| {
            let mut lhs = Ast::Num(NodeId(43), 0.0);
            for (j, state) in STATES.iter().enumerate().take(model.n) {
                if let Some(c) = coefficient(model, i, j) {
                    let der =
                        Ast::Der(NodeId(44), Box::new(Ast::Name(NodeId(45), (*state).into())));
                    lhs = bin(BinOp::Add, lhs, bin(BinOp::Mul, c, der));
                }
            }
            EquationSpec {
                label: format!("e{i}"),
                id: NodeId(46 + i as u32),
                lhs,
                rhs: model.forcing[i].clone(),
            }
        })
        .collect();
    // A tree reading `y` in a one-state model is rejected (unknown name), like any user's.
    let states: Vec<Named<()>> = STATES[..model.n].iter().map(|s| named(s)).collect();
    ModelSpec {
        name: "random".into(),
        params: vec![Named {
            name: "z".into(),
            id: NodeId(49),
            value: Some(1.0),
        }],
        states,
        lets: vec![],
        equations,
        outputs: vec![],
        variants: vec![],
    }
}

pub(super) fn point() -> impl Strategy<Value = [f64; 4]> {
    [0.3f64..2.0, 0.3f64..2.0, 0.3f64..2.0, 0.3f64..2.0]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn compiled_models_solve_their_implicit_equations(model in random_model(), v in point()) {
        let spec = spec(&model);
        let Ok(compiled) = compile(&spec, &CompileOptions::default()) else {
            // Unknown names (a tree reads a state the model lacks), non-finite constants, or a
            // structurally singular matrix: rejected with diagnostics, which is all we ask.
            return Ok(());
        };
        let n = model.n;
        // Trees read [x, y, z]; states are [x, y, w][..n], the parameter is z = v[2].
        let states: Vec<f64> = [v[0], v[1], v[3]][..n].to_vec();
        let tree_point = [v[0], v[1], v[2]];
        let mut m = DMatrix::zeros(n, n);
        for i in 0..n {
            for j in 0..n {
                if let Some(c) = coefficient(&model, i, j) {
                    m[(i, j)] = eval_ast(&c, &tree_point);
                }
            }
        }
        let trees = || model.mass.iter().flatten().chain(&model.forcing);
        if trees().any(|a| ill_conditioned(a, &tree_point)) {
            // The reference itself is not determined to round-off there.
            return Ok(());
        }
        let f = DVector::from_iterator(n, model.forcing.iter().map(|a| eval_ast(a, &tree_point)));
        if !(m.iter().all(|x| x.is_finite()) && f.iter().all(|x| x.is_finite())) {
            return Ok(());
        }
        let sv = m.clone().singular_values();
        let cond = sv.max() / sv.min();
        if cond.is_nan() || cond >= 1e4 {
            return Ok(());
        }
        let want = m.lu().solve(&f).expect("regular");
        let inputs = Inputs { t: 0.0, states: &states, params: &[v[2]], ders: &[] };
        let got = match compiled.rhs.eval(&inputs) {
            Ok(stores) => stores.ders(n),
            // A symbolic pivot that is exactly zero here: reported, never a NaN.
            Err(_) => return Ok(()),
        };
        // The trees work with unit-sized numbers (constants up to 3, angles, points in
        // [0.3, 2]): a result that is round-off of such numbers (cos(atan2(z, 0)) is 6e-17
        // through the calls and exactly 0 through the identities) carries ~1e-16 absolute.
        let scale = want.amax() + f.amax() / sv.max() + 1e-7;
        for i in 0..n {
            prop_assert!(
                (got[i] - want[i]).abs() <= 1e-9 * cond * scale,
                "der {}: {} vs {} (cond {cond:e})\n{}",
                STATES[i], got[i], want[i], compiled.rhs
            );
        }
        let jac = compiled
            .jacobian
            .eval(&inputs)
            .map_err(|e| TestCaseError::fail(format!("{e:?}")))?
            .jacobian(n);
        let fd = compiled.finite_difference_jacobian(&states, &[v[2]], 1e-6).unwrap();
        // The differences are a reference only where they have converged: repeated with
        // twice and half the step they must agree. Next to a pole (tan(tan(x)) at x ≈ 1.61)
        // or where f oscillates faster than the step resolves (sin(tan(y)²) at y ≈ 1.565)
        // they do not, and such entries are skipped: there the reference, not the Jacobian,
        // is what is off.
        let coarse = compiled.finite_difference_jacobian(&states, &[v[2]], 2e-6).unwrap();
        let fine = compiled.finite_difference_jacobian(&states, &[v[2]], 5e-7).unwrap();
        // Differences lose about eps·|f|/h to rounding (h ≈ 1e-6): a huge value with a
        // moderate derivative is beyond them.
        let rounding = 1e-9 * got.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let jscale = fd.iter().flatten().fold(1.0f64, |a, b| a.max(b.abs()));
        for i in 0..n {
            for j in 0..n {
                // A derivative formula may pass through an infinite intermediate (like
                // `atan2(1/atan2(0, x), ..)`) where the value itself is finite: such entries
                // come out non-finite, never wrong; finite ones must match.
                let converged = (coarse[i][j] - fd[i][j]).abs().max((fine[i][j] - fd[i][j]).abs())
                    <= 1e-6 * jscale + 2.0 * rounding;
                if converged && fd[i][j].is_finite() && jac[i][j].is_finite() {
                    prop_assert!(
                        (jac[i][j] - fd[i][j]).abs() <= 1e-5 * jscale + rounding,
                        "jac[{i}][{j}] = {} vs differences {}", jac[i][j], fd[i][j]
                    );
                }
            }
        }
    }
}
