//! Property tests over generated expressions and models.
//!
//! Values are compared at random points against an independent evaluation of the user's tree.
//! Where the tree itself is ill-conditioned at the point (its value moves by more than the
//! tolerance when the inputs move by 1e-13), any two evaluation orders may legitimately differ;
//! the tolerance then grows by that measured spread instead of being loosened everywhere.

use proptest::prelude::*;

use crate::diff::partial;
use crate::eval::Inputs;
use crate::expr::{call_value, ExprId, Sym};
use crate::lower::Lowerer;
use crate::spec::{
    Ast, BinOp, CmpOp, Condition, EquationSpec, Func, ModelSpec, Named, NodeId, VariantSpec,
};
use crate::{compile, CompileOptions};

/// `x`, `y` are states 0, 1; `z` is parameter 0.
const NAMES: [&str; 3] = ["x", "y", "z"];

fn leaf(weird: bool) -> BoxedStrategy<Ast> {
    let mut numbers = vec![0.0, 1.0, 2.0, 0.5, 3.0, 1.5];
    if weird {
        numbers.extend([f64::NAN, f64::INFINITY, -0.0, 1e300]);
    }
    prop_oneof![
        prop::sample::select(numbers).prop_map(|v| Ast::Num(NodeId(1), v)),
        prop::sample::select(NAMES.to_vec()).prop_map(|n| Ast::Name(NodeId(2), n.into())),
    ]
    .boxed()
}

fn func() -> impl Strategy<Value = Func> {
    prop::sample::select(vec![
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Sqrt,
        Func::Exp,
        Func::Ln,
        Func::Abs,
        Func::Sign,
    ])
}

fn cmp_op() -> impl Strategy<Value = CmpOp> {
    prop::sample::select(vec![CmpOp::Lt, CmpOp::Le, CmpOp::Gt, CmpOp::Ge])
}

fn binop() -> impl Strategy<Value = BinOp> {
    prop::sample::select(vec![BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::Div])
}

/// Random expressions over `x, y, z`; with `der`, also time derivatives; with `weird`, also
/// non-finite and huge literals.
pub fn ast(with_der: bool, weird: bool) -> BoxedStrategy<Ast> {
    leaf(weird)
        .prop_recursive(4, 32, 2, move |inner| {
            let b = |a: Ast, b: Ast, op| Ast::Bin(NodeId(3), op, Box::new(a), Box::new(b));
            let mut options = vec![
                (inner.clone(), inner.clone(), binop())
                    .prop_map(move |(x, y, op)| b(x, y, op))
                    .boxed(),
                (inner.clone(), inner.clone(), binop())
                    .prop_map(move |(x, y, op)| b(x, y, op))
                    .boxed(),
                inner
                    .clone()
                    .prop_map(|a| Ast::Neg(NodeId(4), Box::new(a)))
                    .boxed(),
                (inner.clone(), func())
                    .prop_map(|(a, f)| Ast::Call(NodeId(5), f, vec![a]))
                    .boxed(),
                (
                    inner.clone(),
                    inner.clone(),
                    prop::sample::select(vec![Func::Atan2, Func::Hypot]),
                )
                    .prop_map(|(a, c, f)| Ast::Call(NodeId(6), f, vec![a, c]))
                    .boxed(),
                (
                    inner.clone(),
                    inner.clone(),
                    prop::sample::select(vec![Func::Min, Func::Max]),
                )
                    .prop_map(|(a, c, f)| Ast::Call(NodeId(9), f, vec![a, c]))
                    .boxed(),
                (
                    inner.clone(),
                    cmp_op(),
                    inner.clone(),
                    inner.clone(),
                    inner.clone(),
                )
                    .prop_map(|(lhs, op, rhs, a, b)| {
                        let id = NodeId(16);
                        let c = Condition { id, lhs, op, rhs };
                        Ast::If(NodeId(15), Box::new(c), Box::new(a), Box::new(b))
                    })
                    .boxed(),
                (
                    inner.clone(),
                    prop::sample::select(vec![2.0, 3.0, -1.0, 0.5, -2.0, 1.0, 0.0]),
                )
                    .prop_map(move |(a, e)| b(a, Ast::Num(NodeId(7), e), BinOp::Pow))
                    .boxed(),
            ];
            if with_der {
                options.push(
                    inner
                        .clone()
                        .prop_map(|a| Ast::Der(NodeId(8), Box::new(a)))
                        .boxed(),
                );
            }
            proptest::strategy::Union::new(options)
        })
        .boxed()
}

/// Direct evaluation of the user's tree (no `der`). Zero is unsigned, as in the compiler's
/// constants (it only matters on the branch cut of `atan2`).
pub fn eval_ast(a: &Ast, v: &[f64; 3]) -> f64 {
    let r = eval_signed(a, v);
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

/// Below this, an intermediate of the unit-sized trees is round-off: rewritings that are
/// exact (`cos(atan2(z, 0)) = 0`) and calls that are not (`6e-17`) may then differ.
const ROUND_OFF: f64 = 1e-9;

/// Whether evaluating `a` at `v` passes a point where the value is not determined to
/// round-off by its inputs: a comparison (`sign`, `min`, `max`, `if`) of values equal to
/// round-off, `hypot` at its tip (both arguments round-off), `atan2` on its branch cut (`y = 0`, `x ≤ 0`, where the sign of a
/// zero, which `-(a - b)` and `b - a` give differently, picks `±π`), a square root, logarithm,
/// fractional power or division of a round-off-sized number, or `tan` next to a pole. Two
/// correct evaluation orders may disagree there by far more than any tolerance.
pub fn ill_conditioned(a: &Ast, v: &[f64; 3]) -> bool {
    let tiny = |x: f64| x.abs() < ROUND_OFF;
    let near = |x: f64, y: f64| (x - y).abs() < ROUND_OFF * (1.0 + x.abs() + y.abs());
    match a {
        Ast::If(_, c, x, y) => {
            near(eval_ast(&c.lhs, v), eval_ast(&c.rhs, v))
                || [&c.lhs, &c.rhs, x, y].iter().any(|e| ill_conditioned(e, v))
        }
        Ast::Num(..) | Ast::Name(..) | Ast::Der(..) => false,
        Ast::Neg(_, x) => ill_conditioned(x, v),
        Ast::Bin(_, op, l, r) => {
            let here = match op {
                BinOp::Div => tiny(eval_ast(r, v)),
                BinOp::Pow => eval_ast(r, v).fract() != 0.0 && tiny(eval_ast(l, v)),
                _ => false,
            };
            here || ill_conditioned(l, v) || ill_conditioned(r, v)
        }
        Ast::Call(_, f, args) => {
            let x = eval_ast(&args[0], v);
            let here = match f {
                Func::Atan2 => {
                    let along = eval_ast(&args[1], v);
                    tiny(x) && along <= ROUND_OFF
                }
                // The cone's tip, where `hypot` has no derivative.
                Func::Hypot => tiny(x) && tiny(eval_ast(&args[1], v)),
                Func::Sqrt | Func::Ln | Func::Sign => tiny(x),
                Func::Min | Func::Max => near(x, eval_ast(&args[1], v)),
                Func::Tan => tiny(x.cos()),
                _ => false,
            };
            here || args.iter().any(|x| ill_conditioned(x, v))
        }
    }
}

fn eval_signed(a: &Ast, v: &[f64; 3]) -> f64 {
    match a {
        Ast::Num(_, x) => *x,
        Ast::Name(_, n) => v[NAMES.iter().position(|m| m == n).unwrap()],
        Ast::Neg(_, x) => -eval_ast(x, v),
        Ast::Bin(_, op, l, r) => {
            let (l, r) = (eval_ast(l, v), eval_ast(r, v));
            match op {
                BinOp::Add => l + r,
                BinOp::Sub => l - r,
                BinOp::Mul => l * r,
                BinOp::Div => l / r,
                BinOp::Pow => l.powf(r),
            }
        }
        Ast::Call(_, Func::Atan2, args) => eval_ast(&args[0], v).atan2(eval_ast(&args[1], v)),
        Ast::Call(_, Func::Hypot, args) => eval_ast(&args[0], v).hypot(eval_ast(&args[1], v)),
        Ast::Call(_, f @ (Func::Min | Func::Max), args) => {
            let (x, y) = (eval_ast(&args[0], v), eval_ast(&args[1], v));
            match (x.is_nan() || y.is_nan(), f) {
                (true, _) => f64::NAN,
                (false, Func::Min) => x.min(y),
                (false, _) => x.max(y),
            }
        }
        Ast::Call(_, Func::Sign, args) => {
            let x = eval_ast(&args[0], v);
            if x == 0.0 || x.is_nan() {
                x
            } else {
                x.signum()
            }
        }
        Ast::If(_, c, x, y) => {
            let (l, r) = (eval_ast(&c.lhs, v), eval_ast(&c.rhs, v));
            let holds = match c.op {
                CmpOp::Lt => l < r,
                CmpOp::Le => l <= r,
                CmpOp::Gt => l > r,
                CmpOp::Ge => l >= r,
            };
            match (l.is_nan() || r.is_nan(), holds) {
                (true, _) => f64::NAN,
                (false, true) => eval_ast(x, v),
                (false, false) => eval_ast(y, v),
            }
        }
        Ast::Call(_, f, args) => call_value(*f, eval_ast(&args[0], v)),
        Ast::Der(..) => f64::NAN,
    }
}

fn spec_with_outputs(outputs: &[Ast]) -> ModelSpec {
    fn named<T>(name: &str, value: T) -> Named<T> {
        Named {
            name: name.into(),
            id: NodeId(10),
            value,
        }
    }
    let one = || Ast::Num(NodeId(11), 1.0);
    let der = |n: &str| Ast::Der(NodeId(12), Box::new(Ast::Name(NodeId(13), n.into())));
    ModelSpec {
        name: "props".into(),
        params: vec![named("z", None)],
        states: vec![named("x", ()), named("y", ())],
        lets: vec![],
        equations: ["x", "y"]
            .iter()
            .map(|n| EquationSpec {
                label: format!("d{n}"),
                id: NodeId(14),
                lhs: der(n),
                rhs: one(),
            })
            .collect(),
        outputs: outputs
            .iter()
            .enumerate()
            .map(|(k, a)| named(&format!("o{k}"), a.clone()))
            .collect(),
        variants: vec![],
    }
}

/// How much `f` moves when the point moves by a relative 1e-13 (its conditioning here).
fn spread(f: &dyn Fn(&[f64; 3]) -> f64, point: &[f64; 3]) -> f64 {
    let base = f(point);
    let mut worst: f64 = 0.0;
    for pattern in 0..8u32 {
        let p: [f64; 3] = std::array::from_fn(|k| {
            let sign = if pattern >> k & 1 == 1 { 1.0 } else { -1.0 };
            point[k] * (1.0 + sign * 1e-13)
        });
        worst = worst.max((f(&p) - base).abs());
    }
    worst
}

fn close(a: f64, b: f64, reference: &dyn Fn(&[f64; 3]) -> f64, point: &[f64; 3]) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()) + spread(reference, point)
}

fn point() -> impl Strategy<Value = [f64; 3]> {
    [0.3f64..2.0, 0.3f64..2.0, 0.3f64..2.0]
}

fn sym_value(v: &[f64; 3]) -> impl Fn(Sym) -> f64 + '_ {
    move |s| match s {
        Sym::State(i) => v[i],
        Sym::Param(0) => v[2],
        _ => f64::NAN,
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn simplify_preserves_values(a in ast(false, false), v in point()) {
        let spec = spec_with_outputs(std::slice::from_ref(&a));
        let mut lower = Lowerer::new(&spec, vec![None]);
        let Some(e) = lower.output(0) else { return Ok(()); };
        let want = eval_ast(&a, &v);
        let got = lower.pool.eval(e, &sym_value(&v));
        if !want.is_finite() || ill_conditioned(&a, &v) {
            return Ok(());
        }
        prop_assert!(
            close(got, want, &|p| eval_ast(&a, p), &v),
            "simplified {got} vs tree {want}"
        );
    }

    #[test]
    fn derivative_matches_finite_differences(a in ast(false, false), v in point()) {
        let spec = spec_with_outputs(std::slice::from_ref(&a));
        let mut lower = Lowerer::new(&spec, vec![None]);
        let Some(e) = lower.output(0) else { return Ok(()); };
        let d = partial(&mut lower.pool, e, Sym::State(0));
        let got = lower.pool.eval(d, &sym_value(&v));
        let f = |x: f64| eval_ast(&a, &[x, v[1], v[2]]);
        let h = 1e-4;
        let central = |h: f64| (f(v[0] + h) - f(v[0] - h)) / (2.0 * h);
        let (d1, d2) = (central(h), central(h / 2.0));
        let richardson = (4.0 * d2 - d1) / 3.0;
        let scale = 1.0 + richardson.abs() + f(v[0]).abs();
        if !(got.is_finite() && richardson.is_finite()) || (d1 - d2).abs() > 1e-4 * scale {
            // Not smooth enough here (a kink, a pole nearby): differences say nothing.
            return Ok(());
        }
        prop_assert!(
            (got - richardson).abs() <= 1e-6 * scale,
            "symbolic {got} vs differences {richardson}"
        );
    }

    #[test]
    fn program_equals_direct_evaluation(
        exprs in prop::collection::vec(ast(false, false), 1..5),
        v in point(),
    ) {
        let spec = spec_with_outputs(&exprs);
        let Ok(model) = compile(&spec, &CompileOptions::default()) else { return Ok(()); };
        let mut lower = Lowerer::new(&spec, vec![None]);
        let lowered: Vec<ExprId> = (0..exprs.len()).filter_map(|k| lower.output(k)).collect();
        prop_assert_eq!(lowered.len(), exprs.len());
        // The program is emitted after the trigonometric identities, which are exact where the
        // calls they replace round (`cos(atan2(x, 0))` is 0, not 6e-17); they are checked
        // against the calls in `trig`. Here the emission is compared with its own input.
        let system = crate::system::System::default();
        let lowered =
            crate::trig::rewrite(&mut lower.pool, &system, &lowered, &lowered, &|_, _| String::new())
                .outputs;
        let dag = lower.pool.eval_many(&lowered, &sym_value(&v));
        let out = model
            .outputs_program
            .eval(&Inputs { t: 0.0, states: &v[..2], params: &v[2..], ders: &[1.0, 1.0] })
            .unwrap()
            .outputs(exprs.len());
        for k in 0..exprs.len() {
            let tree = eval_ast(&exprs[k], &v);
            if !tree.is_finite() || !dag[k].is_finite() || ill_conditioned(&exprs[k], &v) {
                continue;
            }
            let reference = |p: &[f64; 3]| lower.pool.eval(lowered[k], &sym_value(p));
            prop_assert!(
                close(out[k], dag[k], &reference, &v),
                "output {k}: program {} vs dag {}", out[k], dag[k]
            );
        }
    }

    #[test]
    fn random_specs_never_panic(
        eqs in prop::collection::vec(ast(true, true), 0..4),
        outs in prop::collection::vec(ast(true, true), 0..3),
        n_states in 0usize..3,
        keep in prop::collection::vec(prop::sample::select(vec!["x", "y", "o0", "o1", "zz"]), 0..3),
        fix in prop::collection::vec(
            (prop::sample::select(vec!["z", "x", "q"]), prop::sample::select(vec![0.0, 1.0, f64::NAN])),
            0..2,
        ),
        v in point(),
    ) {
        let mut spec = spec_with_outputs(&outs);
        spec.states.truncate(n_states);
        spec.variants = vec![VariantSpec {
            name: "v".into(),
            id: NodeId(50),
            keep: keep.iter().map(|k| Named { name: (*k).into(), id: NodeId(51), value: () }).collect(),
            fix: fix
                .iter()
                .map(|(k, x)| Named { name: (*k).into(), id: NodeId(52), value: *x })
                .collect(),
        }];
        spec.equations = eqs
            .into_iter()
            .enumerate()
            .map(|(k, e)| EquationSpec {
                label: format!("e{k}"),
                id: NodeId(20 + k as u32),
                lhs: e,
                rhs: Ast::Num(NodeId(30), 0.0),
            })
            .collect();
        match compile(&spec, &CompileOptions::default()) {
            Ok(m) => {
                for model in std::iter::once(&m).chain(&m.variants) {
                    let k = model.states.len();
                    let p = &v[..model.params.len()];
                    let inputs = Inputs { t: 0.0, states: &v[..k], params: p, ders: &v[..k] };
                    let _ = model.rhs.eval(&inputs);
                    let _ = model.jacobian.eval(&inputs);
                    let _ = model.outputs_program.eval(&inputs);
                }
            }
            Err(diags) => prop_assert!(!diags.is_empty()),
        }
    }
}
