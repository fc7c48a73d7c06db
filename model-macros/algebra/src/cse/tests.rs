use super::*;
use crate::eval::Inputs;
use crate::OpCounts;

fn emit(pool: &mut Pool, roots: &[ExprId]) -> Program {
    let system = System::default();
    let input = |s: Sym| match s {
        Sym::State(i) => Some(Operand::State(i)),
        _ => None,
    };
    let mut e = Emitter::new(pool, &system, &input, roots, 0.0);
    for (k, &r) in roots.iter().enumerate() {
        e.store(Target::Output(k), r).unwrap();
    }
    e.finish()
}

#[test]
fn sine_and_cosine_share_one_call() {
    let mut p = Pool::new();
    let x = p.sym(Sym::State(0));
    let s = p.call(Func::Sin, x);
    let c = p.call(Func::Cos, x);
    let e = p.mul2(s, c);
    let prog = emit(&mut p, &[e, s]);
    let sincos = prog
        .stmts
        .iter()
        .filter(|s| matches!(s, Stmt::SinCos { .. }))
        .count();
    assert_eq!(sincos, 1);
    assert_eq!(
        prog.ops(),
        OpCounts {
            mul: 1,
            trig: 1,
            ..OpCounts::default()
        }
    );
}

#[test]
fn integer_powers_and_shared_reciprocals() {
    let mut p = Pool::new();
    let x = p.sym(Sym::State(0));
    let y = p.sym(Sym::State(1));
    let q = p.add2(x, y);
    let x3 = p.powf(x, 3.0);
    let a = p.div(x3, q);
    let b = p.div(y, q);
    let prog = emit(&mut p, &[a, b]);
    assert!(prog.stmts.iter().any(|s| matches!(
        s,
        Stmt::Let {
            node: Op::Powi(Operand::State(0), 3),
            ..
        }
    )));
    // One reciprocal of x + y, two multiplications by it.
    assert_eq!(
        prog.ops(),
        OpCounts {
            add: 1,
            mul: 4,
            div: 1,
            ..OpCounts::default()
        },
        "{prog}"
    );
}

#[test]
fn a_quotient_used_once_is_a_division() {
    let mut p = Pool::new();
    let x = p.sym(Sym::State(0));
    let y = p.sym(Sym::State(1));
    let e = p.div(x, y);
    let prog = emit(&mut p, &[e]);
    assert_eq!(
        prog.ops(),
        OpCounts {
            div: 1,
            ..OpCounts::default()
        }
    );
}

#[test]
fn common_factors_are_pulled_out_of_sums() {
    // x*y + x*z*2 + x  ->  x*(y + 2z + 1): one multiplication by x.
    let mut p = Pool::new();
    let x = p.sym(Sym::State(0));
    let y = p.sym(Sym::State(1));
    let z = p.sym(Sym::State(2));
    let two = p.num(2.0);
    let xy = p.mul2(x, y);
    let xz2 = p.mul(&[x, z, two]);
    let e = p.add(&[xy, xz2, x]);
    let prog = emit(&mut p, &[e]);
    assert_eq!(
        prog.ops(),
        OpCounts {
            add: 2,
            mul: 2,
            ..OpCounts::default()
        },
        "{prog}"
    );
}

#[test]
fn equal_partial_products_are_computed_once() {
    let mut p = Pool::new();
    let v: Vec<ExprId> = (0..4).map(|i| p.sym(Sym::State(i))).collect();
    let a = p.mul(&[v[0], v[1], v[2]]);
    let b = p.mul(&[v[0], v[1], v[3]]);
    let prog = emit(&mut p, &[a, b]);
    // x0*x1 once, then one multiplication each.
    assert_eq!(
        prog.ops(),
        OpCounts {
            mul: 3,
            ..OpCounts::default()
        },
        "{prog}"
    );
}

#[test]
fn an_infinite_coefficient_is_not_pulled_out() {
    // inf*x + inf*y: `inf / inf` is NaN, so pulling `inf` out would give a sum of NaN
    // coefficients to refactor again without end; the sum is emitted as written.
    let mut p = Pool::new();
    let x = p.sym(Sym::State(0));
    let y = p.sym(Sym::State(1));
    let inf = p.num(f64::INFINITY);
    let minus_inf = p.num(f64::NEG_INFINITY);
    let a = p.mul2(inf, x);
    let b = p.mul2(inf, y);
    let c = p.mul2(minus_inf, y);
    let sum = p.add(&[a, b]);
    let difference = p.add(&[a, c]);
    let prog = emit(&mut p, &[sum, difference]);
    assert!(prog.ops().add >= 2, "{prog}");
}

/// The sum the product rule makes of the Jacobian of a chain `n` deep, `s_0 = x`,
/// `s_{k+1} = sin(s_k)`: `Σ_k sin(s_k) / cos(s_k)^2 · Π_{j>k} 1/cos(s_j)`, with the factors
/// it holds (about n²/2).
fn chain_sum(p: &mut Pool, n: usize) -> (ExprId, usize) {
    let mut s = vec![p.sym(Sym::State(0))];
    for k in 0..n {
        let next = p.call(Func::Sin, s[k]);
        s.push(next);
    }
    let cos: Vec<ExprId> = s[..n].iter().map(|&u| p.call(Func::Cos, u)).collect();
    let mut terms = Vec::new();
    let mut size = 0;
    for k in 0..n {
        let mut factors = vec![s[k + 1], p.powf(cos[k], -2.0)];
        for &c in &cos[k + 1..] {
            factors.push(p.powf(c, -1.0));
        }
        size += factors.len();
        terms.push(p.mul(&factors));
    }
    (p.add(&terms), size)
}

/// The value of [`chain_sum`] at `x`, term by term.
fn chain_sum_value(n: usize, x: f64) -> f64 {
    let mut s = vec![x];
    for k in 0..n {
        s.push(s[k].sin());
    }
    (0..n)
        .map(|k| {
            let tail: f64 = s[k + 1..n].iter().map(|u| 1.0 / u.cos()).product();
            s[k].sin() / s[k].cos().powi(2) * tail
        })
        .sum()
}

fn factoring_work(n: usize) -> (usize, usize) {
    let mut p = Pool::new();
    let (sum, size) = chain_sum(&mut p, n);
    let Node::Add(terms) = p.node(sum).clone() else {
        panic!("a sum")
    };
    let factored = factor::factored(&mut p, &terms);
    assert!(factored.expr.is_some());
    (factored.work, size)
}

#[test]
fn factoring_a_chains_jacobian_costs_the_size_of_its_sum() {
    // Factoring one level at a time counted every remaining term again at each of the n
    // levels of the nest: n³ (8x from n = 100 to 200). The work now follows the sum's size
    // (4x), whatever the depth of its nest.
    let (small, small_size) = factoring_work(100);
    let (large, large_size) = factoring_work(200);
    assert_eq!((small_size, large_size), (5150, 20300));
    for (work, size) in [(small, small_size), (large, large_size)] {
        assert!(work <= 3 * size, "{work} for {size} factors");
    }
    let growth = large as f64 / small as f64;
    assert!((3.5..4.5).contains(&growth), "{small} -> {large}");
}

#[test]
fn a_chains_jacobian_is_emitted_as_a_nest_and_keeps_its_value() {
    let n = 200;
    let mut p = Pool::new();
    let (sum, _) = chain_sum(&mut p, n);
    let prog = emit(&mut p, &[sum]);
    // One sine and cosine, one division, and a multiplication and an addition per level.
    let ops = prog.ops();
    assert!(ops.total() <= 6 * n as u32, "{ops:?}");
    for x in [0.3, -1.1, 2.0] {
        let stores = prog
            .eval(&Inputs {
                t: 0.0,
                states: &[x],
                params: &[],
                ders: &[],
            })
            .unwrap();
        let (got, want) = (stores.outputs(1)[0], chain_sum_value(n, x));
        assert!((got - want).abs() <= 1e-12 * want.abs(), "{got} vs {want}");
    }
}
