//! Malformed models: each gives diagnostics at the right node, never a panic.

use crate::common::unchecked as model;
use model_algebra::{compile, CompileOptions};
use model_algebra::{Ast, Diagnostic, ModelSpec, NodeId};

fn diagnose(text: &str) -> (ModelSpec, Vec<Diagnostic>) {
    let spec = model(text);
    let diags = compile(&spec, &CompileOptions::default()).expect_err("must be rejected");
    assert!(!diags.is_empty());
    (spec, diags)
}

/// The node ids of every subexpression of `ast` and their sources, to find a node by text.
fn find<'a>(ast: &'a Ast, pred: &dyn Fn(&Ast) -> bool, out: &mut Vec<&'a Ast>) {
    if pred(ast) {
        out.push(ast);
    }
    for child in ast.children() {
        find(child, pred, out);
    }
}

/// The id of the (first) root-level node of equation `k`'s side matching `pred`.
fn node_in(spec: &ModelSpec, k: usize, pred: &dyn Fn(&Ast) -> bool) -> NodeId {
    let mut out = Vec::new();
    find(&spec.equations[k].lhs, pred, &mut out);
    find(&spec.equations[k].rhs, pred, &mut out);
    out.first().expect("node").id()
}

macro_rules! rejected {
    ($($name:ident: $text:expr => $needle:expr;)*) => {$(
        #[test]
        fn $name() {
            let (_, diags) = diagnose($text);
            assert!(
                diags.iter().any(|d| d.message.contains($needle)),
                "expected a diagnostic containing {:?}, got {:#?}",
                $needle,
                diags
            );
        }
    )*};
}

rejected! {
    product_of_derivatives: "mod m { states { x, y } equations { a: der(x)*der(y) = 1; b: der(y) = x; } }"
        => "a product of two derivatives";
    function_of_derivative: "mod m { states { x } equations { a: sin(der(x)) = 1; } }" => "`sin` of a derivative";
    division_by_derivative: "mod m { states { x } equations { a: 1/der(x) = 1; } }" => "a division by a derivative";
    square_of_derivative: "mod m { states { x } equations { a: der(x)^2 = 1; } }" => "a power of a derivative";
    sign_of_derivative: "mod m { states { x } equations { a: sign(der(x)) = 1; } }" => "`sign` of a derivative";
    max_of_derivative: "mod m { states { x } equations { a: max(der(x), 0) = 1; } }" => "`max` of a derivative";
    min_of_derivative_through_let: "mod m { states { x } let d = der(x); equations { a: min(1, d) = x; } }"
        => "`min` of a derivative";
    condition_on_derivative: "mod m { states { x } equations { a: if(der(x) > 0, 1, 2) + der(x) = 0; } }"
        => "a condition on a derivative";
    nonlinear_through_let: "mod m { states { x, y } let v = der(x); equations { a: v*der(y) = 1; b: der(y) = 1; } }"
        => "a product of two derivatives";
    second_derivative: "mod m { states { x } equations { a: der(der(x)) = 1; } }" => "only first derivatives";
    structurally_singular: "mod m { states { x, y, z } equations { R4: der(x) = 1; R5: 2*der(x) = y; R6: der(y) + der(z) = 0; } }"
        => "structurally singular: R4, R5 (2 equations) contain only der(x) (1 derivative), so `R5` is one equation too many, and nothing is left to determine one of der(y), der(z)";
    unused_derivative: "mod m { states { x, y } equations { a: der(x) = y; b: der(x) = 1; } }"
        => "no equation contains der(y), so nothing determines `y`";
    too_many_equations: "mod m { states { x } equations { a: der(x) = 1; b: der(x) = 2; } }"
        => "a, b (2 equations) contain only der(x) (1 derivative), so `b` is one equation too many";
    too_few_equations_sharing: "mod m { states { x, y, z } equations { a: der(x) = y; b: der(y) + der(z) = 1; } }"
        => "too few equations: der(y), der(z) share 1 equation (b); add an equation for one of der(y), der(z)";
    algebraic_equation: "mod m { states { x, y } equations { a: der(x) = y; b: x = y; } }"
        => "b contains no derivative: algebraic equations (constraints) are not supported";
    cancelled_derivatives_leave_an_algebraic_equation: "mod m { states { x } equations { a: der(x) - der(x) + x = 1; } }"
        => "a contains no derivative";
    no_states: "mod m { params { m = 1 } }" => "no states";
    too_few_equations: "mod m { states { x, y } equations { a: der(x) = y; } }" => "nothing determines `y`";
    unknown_name: "mod m { states { x } equations { a: der(x) = not_declared; } }" => "unknown name";
    division_by_zero: "mod m { states { x } equations { a: der(x) = x/0; } }" => "division by zero";
    log_of_zero: "mod m { states { x } equations { a: der(x) = x + ln(0); } }" => "not finite";
    zero_to_negative_power: "mod m { states { x } equations { a: der(x) = 0^(0-1); } }" => "not finite";
    let_cycle: "mod m { states { x } let a = b + 1; let b = a*x; equations { e: der(x) = a; } }" => "depends on itself";
    output_before_definition: "mod m { states { x } equations { e: der(x) = 1; } outputs { o1 = o2; o2 = x; } }" => "used before it is defined";
    output_in_equation: "mod m { states { x } equations { e: der(x) = o; } outputs { o = x; } }" => "only be used in later outputs";
    cancelling_coefficients: "mod m { states { x, y } equations { a: der(x) + der(y) = 1; b: 2*der(x) + 2*der(y) = x; } }"
        => "singular";
    variant_keeps_unknown: "mod m { states { x } equations { e: der(x) = 1; } variant v { keep { nothing_here } } }" => "neither a state nor an output";
    variant_fixes_unknown: "mod m { states { x } equations { e: der(x) = 1; } variant v { keep { x } fix { q = 1 } } }" => "not a parameter";
}

#[test]
fn nonlinear_diagnostic_points_at_the_operator() {
    let (spec, diags) =
        diagnose("mod m { states { x, y } equations { a: x*der(x)*der(y) = 1; b: der(y) = x; } }");
    let mul = node_in(&spec, 0, &|a| {
        matches!(a, Ast::Bin(_, model_algebra::BinOp::Mul, _, r) if matches!(**r, Ast::Der(..)))
            && matches!(a, Ast::Bin(_, _, l, _) if matches!(**l, Ast::Bin(..)))
    });
    assert_eq!(diags.len(), 1, "{diags:#?}");
    assert_eq!(diags[0].id, mul);
}

#[test]
fn non_finite_literal_is_reported_at_the_literal() {
    let mut spec = model("mod m { states { x } equations { a: der(x) = 1; } }");
    let id = NodeId(999);
    spec.equations[0].rhs = Ast::Num(id, f64::NAN);
    let diags = compile(&spec, &CompileOptions::default()).unwrap_err();
    assert_eq!(diags[0].id, id);
    assert!(diags[0].message.contains("not finite"));
}

#[test]
fn all_errors_of_a_model_are_reported_together() {
    let (_, diags) =
        diagnose("mod m { states { x, y } equations { a: der(x)*der(y) = 1; b: der(y) = x/0; } outputs { o = zz; } }");
    assert_eq!(diags.len(), 3, "{diags:#?}");
}

#[test]
fn singular_block_points_at_the_equation_too_many() {
    let (spec, diags) = diagnose(
        "mod m { states { x, y, z } equations { R4: der(x) = 1; R5: 2*der(x) = y; R6: der(y) + der(z) = 0; } }",
    );
    assert_eq!(diags.len(), 1, "{diags:#?}");
    assert_eq!(diags[0].id, spec.equations[1].id);
}

#[test]
fn too_few_equations_point_at_a_state_without_one() {
    let (spec, diags) = diagnose(
        "mod m { states { x, y, z } equations { a: der(x) = y; b: der(y) + der(z) = 1; } }",
    );
    assert_eq!(diags.len(), 1, "{diags:#?}");
    assert_eq!(diags[0].id, spec.states[1].id);
}
