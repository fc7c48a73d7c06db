use super::messages;
use crate::parse::parse_model;
use crate::validate::validate;
use model_algebra::Ast;
use proc_macro2::TokenStream;
use quote::quote;

fn errors_of(tokens: TokenStream) -> Vec<String> {
    let ast = parse_model(tokens).expect("the test model parses");
    match validate(&ast) {
        Ok(_) => Vec::new(),
        Err(error) => messages(error),
    }
}

/// Each row: a model body (inside `mod m { .. }`) and the messages it must produce, in order.
macro_rules! rejects {
    ($($name:ident: { $($body:tt)* } => [$($message:literal),* $(,)?];)*) => {$(
        #[test]
        fn $name() {
            let found = errors_of(quote!(mod m { $($body)* }));
            let expected: &[&str] = &[$($message),*];
            assert_eq!(found.len(), expected.len(), "{found:#?}");
            for (found, expected) in found.iter().zip(expected) {
                assert!(found.contains(expected), "`{found}` should contain `{expected}`");
            }
        }
    )*};
}

rejects! {
    unknown_name_lists_the_declared_ones: {
        params { k } states { x } equations { der(x) = -k * z; }
    } => ["unknown name `z`; usable here: parameters `k`; states `x`; `t` and `pi`"];
    name_declared_twice: {
        params { k } states { x, k } equations { der(x) = 1; der(k) = 1; }
    } => ["`k` is declared twice: it is already a parameter"];
    time_is_reserved: {
        states { t } equations { der(t) = 1; }
    } => ["`t` is reserved: it is the time (built in)"];
    function_names_are_reserved: {
        states { x } let sin = x; equations { der(x) = 1; }
    } => ["`sin` is reserved: it is a function (built in)"];
    der_of_a_parameter: {
        params { k } states { x } equations { der(x) + der(k) = 0; }
    } => ["`der(k)`: `k` is a parameter, which is constant"];
    der_of_an_expression_without_state: {
        params { k } states { x } let c = 2 * k; equations { der(x) + der(c * pi) = 0; }
    } => ["`der` of an expression with no state and no `t`"];
    der_of_time_is_fine_but_nested_der_is_not: {
        states { x } let v = der(x); equations { der(v) + der(t) = 0; }
    } => ["nested `der`"];
    no_states: {
        params { k }
    } => ["the model has no states"];
    output_used_before_it_is_defined: {
        states { x } equations { der(x) = 1; } outputs { a = b + 1; b = x; }
    } => ["output `b` is used before it is defined: outputs are computed in order, so move `b` above `a`"];
    output_used_in_an_equation: {
        states { x } equations { der(x) = e; } outputs { e = x; }
    } => ["`e` is an output"];
    output_refers_to_itself: {
        states { x } equations { der(x) = 1; } outputs { e = e + x; }
    } => ["output `e` refers to itself"];
    cycle_among_lets_is_named: {
        states { x } let a = b + x; let b = c; let c = a * 2; equations { der(x) = a; }
    } => ["cycle among lets: `a` -> `b` -> `c` -> `a`"];
    wrong_number_of_arguments: {
        states { x } equations { der(x) = atan2(x) + sin(x, x); }
    } => ["`atan2` takes 2 arguments, found 1", "`sin` takes 1 argument, found 2"];
    hypot_takes_two_arguments: {
        states { x } equations { der(x) = hypot(x) + hypot(x, x, x); }
    } => ["`hypot` takes 2 arguments, found 1", "`hypot` takes 2 arguments, found 3"];
    unknown_function: {
        states { x } equations { der(x) = sine(x); }
    } => ["unknown function `sine` (did you mean `sin`?); the functions are `sin`, `cos`, `tan`, `sqrt`, `exp`, `ln`, `abs`, `atan2`, `hypot`, `sign`, `min`, `max`, `der` and `if(x > y, a, b)`"];
    a_misspelt_name_gets_a_suggestion: {
        states { theta, omega } equations { der(theta) = omgea; der(omega) = -sin(theta); }
    } => ["unknown name `omgea` (did you mean `omega`?); usable here: states `theta`, `omega`"];
    a_state_is_not_a_function: {
        states { x } equations { der(x) = x(1); }
    } => ["`x` is a state, not a function"];
    a_function_is_not_a_value: {
        states { x } equations { der(x) = cos; }
    } => ["`cos` is a function: call it as `cos(..)`"];
    variant_keeps_an_unknown_quantity: {
        params { k } states { x } equations { der(x) = k; }
        variant v { keep { y } fix { k = 1 } }
    } => ["variant `v` keeps `y`, which is not a state or an output; states `x`"];
    variant_fixes_an_unknown_parameter: {
        params { k } states { x } equations { der(x) = k; }
        variant v { keep { x } fix { q = 1 } }
    } => ["variant `v` fixes `q`, which is not a parameter; parameters `k`"];
    variant_cannot_shadow_an_emitted_module: {
        states { x } equations { der(x) = 1; } variant state { keep { x } }
    } => ["a variant cannot be called `state`"];
    unknown_option: {
        states { x } equations { der(x) = 1; } options { swell = 3 }
    } => ["unknown option `swell`; the options are `swell_bound` (the most operations"];
    pivot_tolerance_is_a_fraction: {
        states { x } equations { der(x) = 1; } options { pivot_tolerance = 1 }
    } => ["`pivot_tolerance` must be at least 0 and below 1, not 1"];
    swell_bound_is_a_whole_number: {
        states { x } equations { der(x) = 1; } options { swell_bound = 1.5 }
    } => ["`swell_bound` must be a whole number of operations, not 1.5"];
    only_doc_comments_on_names: {
        params { #[inline] k } states { x } equations { der(x) = k; }
    } => ["only doc comments (`/// ..`) are allowed in a model"];
    duplicate_labels: {
        states { x, y } equations { a: der(x) = 1; a: der(y) = 1; }
    } => ["equation label `a` is used twice"];
    every_error_is_reported_at_once: {
        params { k } states { x, y } equations { der(x) = q; der(y) = foo(x) + der(k); }
    } => ["unknown name `q`", "unknown function `foo`", "`der(k)`"];
}

#[test]
fn edit_distances() {
    use crate::names::edit_distance;
    for (a, b, distance) in [
        ("", "", 0),
        ("x", "", 1),
        ("sine", "sin", 1),
        ("omgea", "omega", 2),
        ("theta", "theta", 0),
        ("kitten", "sitting", 3),
    ] {
        assert_eq!(edit_distance(a, b), distance, "{a} -> {b}");
        assert_eq!(edit_distance(b, a), distance, "{b} -> {a}");
    }
}

#[test]
fn a_valid_model_resolves_to_the_spec() {
    let ast = parse_model(quote! {
        mod pend {
            params { g = 9.81, l }
            states { phi, omega }
            let s = sin(phi);
            equations { kin: der(phi) = omega; der(omega) = -g / l * s; }
            outputs { e = omega^2 / 2 - g / l * cos(phi); p = e * der(omega); }
            variant v { keep { omega } fix { g = 1 } }
        }
    })
    .unwrap();
    let spec = validate(&ast).unwrap().remove(0).spec;
    assert_eq!(spec.name, "pend");
    assert_eq!(spec.equations[0].label, "kin");
    assert_eq!(spec.equations[1].label, "equation 2");
    assert!(
        matches!(&spec.equations[0].lhs, Ast::Der(_, arg) if **arg == Ast::Name(arg.id(), "phi".into()))
    );
    assert_eq!(spec.outputs.len(), 2);
    assert_eq!(spec.variants[0].fix[0].value, 1.0);
    // Every node id points into the span table.
    let mut ids = Vec::new();
    fn collect(ast: &Ast, ids: &mut Vec<u32>) {
        ids.push(ast.id().0);
        for child in ast.children() {
            collect(child, ids);
        }
    }
    for eq in &spec.equations {
        collect(&eq.lhs, &mut ids);
        collect(&eq.rhs, &mut ids);
    }
    assert!(ids
        .iter()
        .all(|&id| ast.spans.get(model_algebra::NodeId(id)).is_some()));
}
