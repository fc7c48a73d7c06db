//! The block solve against nalgebra's LU on random dense and sparse systems.
//!
//! Coefficients are random expressions of three symbols; the matrices are strongly diagonally
//! dominant everywhere (an off-diagonal entry is at most a twentieth of its diagonal), so the
//! threshold guard of the pivot choice only accepts diagonal pivots, elimination in that order
//! is stable, and a 1e-12 agreement is a fair demand on both the symbolic and the numeric path.

use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

use crate::cse::Emitter;
use crate::eval::Inputs;
use crate::expr::{ExprId, Pool, Sym};
use crate::program::{Operand, Target};
use crate::solve::{solve_block, BlockSystem, Sampler, SolveContext};
use crate::spec::Func;
use crate::system::{Body, System};

/// One random coefficient: `weight * (1 + 0.5 * f(s_a ∘ s_b))`.
#[derive(Clone, Debug)]
struct Coefficient {
    weight: f64,
    pattern: u8,
    a: usize,
    b: usize,
}

impl Coefficient {
    fn build(&self, pool: &mut Pool) -> ExprId {
        let (a, b) = (pool.sym(Sym::State(self.a)), pool.sym(Sym::State(self.b)));
        let inner = match self.pattern {
            0 => {
                let m = pool.mul2(a, b);
                pool.call(Func::Sin, m)
            }
            1 => {
                let m = pool.mul2(a, b);
                pool.call(Func::Cos, m)
            }
            2 => {
                let s = pool.add2(a, b);
                pool.call(Func::Sin, s)
            }
            _ => {
                let d = pool.sub(a, b);
                pool.call(Func::Cos, d)
            }
        };
        let half = pool.num(0.5);
        let h = pool.mul2(half, inner);
        let g = pool.add2(ExprId::ONE, h);
        let w = pool.num(self.weight);
        pool.mul2(w, g)
    }
}

fn coefficient(weights: std::ops::Range<f64>) -> impl Strategy<Value = Coefficient> {
    (weights, 0u8..4, 0usize..3, 0usize..3).prop_map(|(weight, pattern, a, b)| Coefficient {
        weight,
        pattern,
        a,
        b,
    })
}

#[derive(Clone, Debug)]
struct RandomSystem {
    n: usize,
    /// Row-major; `None` is a structural zero.
    matrix: Vec<Option<Coefficient>>,
    rhs: Vec<Coefficient>,
}

fn system(sparse: bool) -> impl Strategy<Value = RandomSystem> {
    (1usize..=8).prop_flat_map(move |n| {
        let density = 0.3;
        let cells: Vec<BoxedStrategy<Option<Coefficient>>> = (0..n * n)
            .map(|k| {
                if k / n == k % n {
                    coefficient(60.0..80.0).prop_map(Some).boxed()
                } else if sparse {
                    prop::option::weighted(density, coefficient(-1.0..1.0)).boxed()
                } else {
                    coefficient(-1.0..1.0).prop_map(Some).boxed()
                }
            })
            .collect();
        (cells, prop::collection::vec(coefficient(-5.0..5.0), n))
            .prop_map(move |(matrix, rhs)| RandomSystem { n, matrix, rhs })
    })
}

/// Solves symbolically (or numerically, with `swell_bound` 0) and compares with nalgebra.
fn check(sys: &RandomSystem, point: [f64; 3], swell_bound: usize) -> Result<(), TestCaseError> {
    let mut pool = Pool::new();
    let matrix: Vec<ExprId> = sys
        .matrix
        .iter()
        .map(|c| c.as_ref().map_or(ExprId::ZERO, |c| c.build(&mut pool)))
        .collect();
    let rhs: Vec<ExprId> = sys.rhs.iter().map(|c| c.build(&mut pool)).collect();
    let block = BlockSystem {
        matrix: matrix.clone(),
        rhs: rhs.clone(),
        vars: (0..sys.n).collect(),
    };
    let sampler = Sampler {
        param: &|_| 1.0,
        n_states: 3,
    };
    let ctx = SolveContext {
        text: &|_, _| "pivot".into(),
        sampler: &sampler,
        swell_bound,
    };
    let solution =
        solve_block(&mut pool, &block, &ctx).map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
    let numeric = matches!(solution.group.body, Body::Numeric { .. });
    let over_bound = solution
        .symbolic_ops
        .is_none_or(|ops| ops as usize > swell_bound);
    prop_assert_eq!(numeric, sys.n > 1 && over_bound);
    if swell_bound == usize::MAX {
        prop_assert!(!numeric, "diagonally dominant blocks have safe pivots");
    }
    let mut system = System::default();
    system.push(solution.group);
    let ders: Vec<ExprId> = (0..sys.n).map(|i| pool.sym(Sym::Der(i))).collect();
    let input = |s: Sym| match s {
        Sym::State(i) => Some(Operand::State(i)),
        _ => None,
    };
    let mut e = Emitter::new(&mut pool, &system, &input, &ders, 0.0);
    for (i, &d) in ders.iter().enumerate() {
        e.store(Target::Der(i), d).expect("bound");
    }
    let program = e.finish();
    let got = program
        .eval(&Inputs {
            t: 0.0,
            states: &point,
            params: &[],
            ders: &[],
        })
        .expect("regular")
        .ders(sys.n);

    let value = |s: Sym| match s {
        Sym::State(i) => point[i],
        _ => f64::NAN,
    };
    let a = DMatrix::from_row_slice(sys.n, sys.n, &pool.eval_many(&matrix, &value));
    let b = DVector::from_vec(pool.eval_many(&rhs, &value));
    let want = a.lu().solve(&b).expect("nonsingular");
    let scale = want.amax();
    for i in 0..sys.n {
        prop_assert!(
            (got[i] - want[i]).abs() <= 1e-12 * scale,
            "x[{}] = {} but LU gives {}",
            i,
            got[i],
            want[i]
        );
    }
    Ok(())
}

fn point() -> impl Strategy<Value = [f64; 3]> {
    [0.3f64..2.0, 0.3f64..2.0, 0.3f64..2.0]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn dense_systems_symbolic(sys in system(false), p in point()) {
        check(&sys, p, usize::MAX)?;
    }

    #[test]
    fn dense_systems_numeric(sys in system(false), p in point()) {
        check(&sys, p, 0)?;
    }

    #[test]
    fn sparse_systems_symbolic(sys in system(true), p in point()) {
        check(&sys, p, usize::MAX)?;
    }

    #[test]
    fn sparse_systems_numeric(sys in system(true), p in point()) {
        check(&sys, p, 0)?;
    }
}
