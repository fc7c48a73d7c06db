//! The emitter on hand-made programs: every statement kind becomes the Rust it should, and the
//! whole expansion is valid Rust.

use crate::emit::emit;
use model_algebra::Func;
use model_algebra::{CompiledModel, Node, Operand, Program, Stmt, SumCheck, Target};
use model_dsl::parse_model;
use quote::quote;

fn compiled() -> CompiledModel {
    let rhs = Program {
        stmts: vec![
            Stmt::SinCos {
                sin: 0,
                cos: 1,
                arg: Operand::State(0),
            },
            Stmt::CheckPivot {
                value: Operand::Tmp(0),
                text: "sin(a)".into(),
                sums: vec![],
                tolerance: 0.0,
            },
            Stmt::Let {
                tmp: 2,
                node: Node::Div(Operand::Tmp(1), Operand::Tmp(0)),
            },
            Stmt::CheckPivot {
                value: Operand::Tmp(1),
                text: "cos(a) - a".into(),
                sums: vec![SumCheck {
                    sum: Operand::Tmp(1),
                    magnitude: Operand::Tmp(2),
                }],
                tolerance: 1e-12,
            },
            Stmt::Let {
                tmp: 3,
                node: Node::Powi(Operand::Const(-2.0), 3),
            },
            Stmt::Let {
                tmp: 4,
                node: Node::Call(Func::Sqrt, Operand::Param(0)),
            },
            Stmt::SolveBlock {
                n: 2,
                matrix: vec![
                    Operand::Tmp(2),
                    Operand::Const(1.0),
                    Operand::Const(1.0),
                    Operand::Tmp(3),
                ],
                rhs: vec![Operand::Time, Operand::Tmp(4)],
                result: vec![5, 6],
                text: "der(a), der(b)".into(),
            },
            Stmt::Store {
                target: Target::Der(0),
                value: Operand::Tmp(5),
            },
            Stmt::Store {
                target: Target::Der(1),
                value: Operand::Tmp(6),
            },
        ],
    };
    let outputs_program = Program {
        stmts: vec![
            Stmt::Let {
                tmp: 0,
                node: Node::Call2(Func::Atan2, Operand::Der(0), Operand::State(1)),
            },
            Stmt::Let {
                tmp: 1,
                node: Node::Call(Func::Sign, Operand::State(0)),
            },
            Stmt::Let {
                tmp: 2,
                node: Node::Select(
                    Operand::Tmp(0),
                    Operand::Const(0.5),
                    Operand::Tmp(1),
                    Operand::Param(0),
                ),
            },
            Stmt::Let {
                tmp: 3,
                node: Node::Call2(Func::Hypot, Operand::Tmp(2), Operand::Der(1)),
            },
            Stmt::Store {
                target: Target::Output(0),
                value: Operand::Tmp(3),
            },
        ],
    };
    CompiledModel {
        name: "m".into(),
        states: vec!["a".into(), "b".into()],
        params: vec![("k".into(), Some(-1.5))],
        outputs: vec!["o".into()],
        rhs,
        jacobian: Program {
            stmts: vec![Stmt::Store {
                target: Target::Jac(1, 0),
                value: Operand::Const(0.5),
            }],
        },
        outputs_program,
        pivots: vec!["sin(a)".into()],
        numeric_blocks: vec!["der(a), der(b)".into()],
        variants: Vec::new(),
        explanation: Default::default(),
        initial: vec![Some(2.0), None],
    }
}

#[test]
fn constants_read_back_exactly() {
    for value in [
        0.1,
        -0.0,
        1e300,
        -2.5e-300,
        1.0 / 3.0,
        f64::MIN_POSITIVE,
        123456789.0,
    ] {
        let text = crate::emit_program::constant(value).to_string();
        let expr: syn::Expr = syn::parse_str(&text).unwrap();
        let (negative, literal) = match expr {
            syn::Expr::Paren(paren) => match *paren.expr {
                syn::Expr::Unary(unary) => (true, *unary.expr),
                other => panic!("{other:?}"),
            },
            other => (false, other),
        };
        let syn::Expr::Lit(syn::ExprLit {
            lit: syn::Lit::Float(float),
            ..
        }) = literal
        else {
            panic!("`{text}` is not a float literal");
        };
        assert_eq!(float.suffix(), "f64");
        let magnitude: f64 = float.base10_parse().unwrap();
        let read = if negative { -magnitude } else { magnitude };
        assert_eq!(read.to_bits(), value.to_bits(), "{text}");
    }
}

fn normalized(tokens: proc_macro2::TokenStream) -> String {
    tokens
        .to_string()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

#[test]
fn each_statement_kind_is_translated() {
    let ast = parse_model(quote! {
        mod m { params { k = -1.5 } states { a, b } equations { der(a) = 1; der(b) = 1; } outputs { o = a; } }
    })
    .unwrap();
    let output = emit(&ast, &compiled());
    // The whole expansion is valid Rust.
    syn::parse2::<syn::File>(output.clone()).expect("the expansion parses as Rust");
    let text = normalized(output);
    for expected in [
        "let (t0 , t1) = y [0] . sin_cos () ;",
        "if ! (t0 != 0.0 && t0 . is_finite ()) { return :: core :: result :: Result :: Err (:: model_runtime :: EvalError :: singular (MODEL_NAME , \"sin(a)\" , t0)) ; }",
        "let t2 : f64 = t1 / t0 ;",
        "if ! (t1 != 0.0 && t1 . is_finite ()) || t1 . abs () <= 1e-12_f64 * t2 { return :: core :: result :: Result :: Err (:: model_runtime :: EvalError :: singular (MODEL_NAME , \"cos(a) - a\" , t1)) ; }",
        "let t3 : f64 = (- 2.0_f64) . powi (3) ;",
        "let t4 : f64 = p [0] . sqrt () ;",
        "let [t5 , t6] = :: model_runtime :: solve_block ::< 2 > ([[t2 , 1.0_f64] , [1.0_f64 , t3]] , [t , t4] , MODEL_NAME , \"der(a), der(b)\") ?;",
        "dy [0] = t5 ;",
        "let t0 : f64 = dy [0] . atan2 (y [1]) ;",
        "let t1 : f64 = if y [0] > 0.0 { 1.0 } else if y [0] < 0.0 { - 1.0 } else { y [0] } ;",
        "let t2 : f64 = if t0 > 0.5_f64 { t1 } else if t0 <= 0.5_f64 { p [0] } else { f64 :: NAN } ;",
        "let t3 : f64 = t2 . hypot (dy [1]) ;",
        "jac [0] [0] = 0.0 ;",
        "jac [1] [0] = 0.5_f64 ;",
        "pub const a : usize = 0usize ;",
        "pub const PARAM_DEFAULTS : [:: core :: option :: Option < f64 > ; N_PARAMS] = [:: core :: option :: Option :: Some ((- 1.5_f64))] ;",
        "Model :: new ([(- 1.5_f64)])",
        "pivots : :: model_runtime :: Names :: Static (& [\"sin(a)\"])",
        "const DER_NAMES : [& str ; N_STATES] = [\"der(a)\" , \"der(b)\"] ;",
    ] {
        assert!(text.contains(expected), "missing `{expected}` in\n{text}");
    }
    // Stored entries are not zeroed first.
    assert!(!text.contains("jac [1] [0] = 0.0 ;"));
    assert!(!text.contains("dy [0] = 0.0 ;"));
}

#[test]
fn a_parameter_without_default_means_no_default_impl() {
    let ast = parse_model(quote! { mod m { params { k } states { a, b } } }).unwrap();
    let mut model = compiled();
    model.params = vec![("k".into(), None)];
    let text = normalized(emit(&ast, &model));
    assert!(!text.contains("Default for Model"));
}
