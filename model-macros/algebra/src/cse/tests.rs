use super::*;
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
