//! The emitter on hand-made programs: every statement kind becomes the Rust it should, and the
//! whole expansion is valid Rust.

use crate::emit::emit;
use crate::parse::parse_model;
use model_algebra::program::{CompiledModel, Node, Operand, Program, Stmt, Target};
use model_algebra::spec::Func;
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
            },
            Stmt::Let {
                tmp: 2,
                node: Node::Div(Operand::Tmp(1), Operand::Tmp(0)),
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
                node: Node::Atan2(Operand::Der(0), Operand::State(1)),
            },
            Stmt::Store {
                target: Target::Output(0),
                value: Operand::Tmp(0),
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
        "let (t0 , t1) = y [0usize] . sin_cos () ;",
        "if ! (t0 != 0.0 && t0 . is_finite ()) { return :: core :: result :: Result :: Err (:: model_runtime :: EvalError :: SingularPivot { model : MODEL_NAME , pivot : \"sin(a)\" , value : t0 , }) ; }",
        "let t2 : f64 = t1 / t0 ;",
        "let t3 : f64 = (- 2f64) . powi (3i32) ;",
        "let t4 : f64 = p [0usize] . sqrt () ;",
        "let [t5 , t6] = :: model_runtime :: linalg :: solve_block :: < 2usize > ([[t2 , 1f64] , [1f64 , t3]] , [t , t4] , MODEL_NAME , \"der(a), der(b)\" ,) ? ;",
        "dy [0usize] = t5 ;",
        "let t0 : f64 = dy [0usize] . atan2 (y [1usize]) ;",
        "jac [0usize] [0usize] = 0.0 ;",
        "jac [1usize] [0usize] = 0.5f64 ;",
        "pub const a : usize = 0usize ;",
        "pub const PARAM_DEFAULTS : [:: core :: option :: Option < f64 > ; N_PARAMS] = [:: core :: option :: Option :: Some ((- 1.5f64))] ;",
        "Model :: new ([(- 1.5f64)])",
        "pivots : & [\"sin(a)\"]",
        "const DER_NAMES : [& str ; N_STATES] = [\"der(a)\" , \"der(b)\"] ;",
    ] {
        assert!(text.contains(expected), "missing `{expected}` in\n{text}");
    }
    // Stored entries are not zeroed first.
    assert!(!text.contains("jac [1usize] [0usize] = 0.0 ;"));
    assert!(!text.contains("dy [0usize] = 0.0 ;"));
}

#[test]
fn a_parameter_without_default_means_no_default_impl() {
    let ast = parse_model(quote! { mod m { params { k } states { a, b } } }).unwrap();
    let mut model = compiled();
    model.params = vec![("k".into(), None)];
    let text = normalized(emit(&ast, &model));
    assert!(!text.contains("Default for Model"));
}
