//! `sign`, `min`, `max` and `if(COND, a, b)`: how they parse, and the mistakes around them.

use super::{messages, show};
use crate::parse::parse_model;
use crate::validate::validate;
use model_algebra::{Ast, CmpOp, Func};
use proc_macro2::TokenStream;
use quote::quote;

/// The let `e` of a minimal model around `expr`, shown fully parenthesised.
fn parsed(expr: TokenStream) -> String {
    let model = parse_model(quote! {
        mod m { states { x, y } let e = #expr; equations { der(x) = 0; der(y) = 0; } }
    })
    .expect("the test model parses");
    show(&model.lets[0].value)
}

/// The messages of parsing and validating `mod m { body }`.
fn errors_of(body: TokenStream) -> Vec<String> {
    match parse_model(quote!(mod m { #body })) {
        Err(error) => messages(error),
        Ok(ast) => validate(&ast).err().map(messages).unwrap_or_default(),
    }
}

#[test]
fn conditions_and_the_new_functions_parse_as_operands() {
    let rows = [
        (quote!(if(x > y, x + 1, -y)), "if(x>y,(x+1),(-y))"),
        (quote!(if(x - 1 <= 2 * y, 1, 2)), "if((x-1)<=(2*y),1,2)"),
        (quote!(2 * if(x < 0, 1, 2)^2), "(2*(if(x<0,1,2)^2))"),
        (
            quote!(if(x >= 0, if(y < 1, 1, 2), 3)),
            "if(x>=0,if(y<1,1,2),3)",
        ),
        (quote!(max(0, 3 * (1 - x))), "max(0,(3*(1-x)))"),
        (quote!(-x * sign(x - y)), "((-x)*sign((x-y)))"),
        (quote!(min(x, y) + 1), "(min(x,y)+1)"),
    ];
    for (expr, expected) in rows {
        assert_eq!(parsed(expr), expected);
    }
}

#[test]
fn conditions_resolve_to_the_algebras_comparisons() {
    let ast = parse_model(quote! {
        mod m { states { x } equations { der(x) = if(x >= 1, max(x, 2), sign(x)); } }
    })
    .unwrap();
    let spec = validate(&ast).unwrap().remove(0).spec;
    let Ast::If(_, cond, then, otherwise) = &spec.equations[0].rhs else {
        panic!("not an if: {:?}", spec.equations[0].rhs);
    };
    assert_eq!(cond.op, CmpOp::Ge);
    assert!(matches!(&**then, Ast::Call(_, Func::Max, args) if args.len() == 2));
    assert!(matches!(&**otherwise, Ast::Call(_, Func::Sign, _)));
}

/// Each row: a model body and the messages it must produce, in order.
macro_rules! rejects {
    ($($name:ident: { $($body:tt)* } => [$($message:literal),* $(,)?];)*) => {$(
        #[test]
        fn $name() {
            let found = errors_of(quote!($($body)*));
            let expected: &[&str] = &[$($message),*];
            assert_eq!(found.len(), expected.len(), "{found:#?}");
            for (found, expected) in found.iter().zip(expected) {
                assert!(found.contains(expected), "`{found}` should contain `{expected}`");
            }
        }
    )*};
}

rejects! {
    equality_is_no_condition: {
        states { x } equations { der(x) = if(x == 0, 1, 2); }
    } => ["`if` cannot test `==`: computed values are practically never exactly equal"];
    a_condition_needs_a_comparison: {
        states { x } equations { der(x) = if(x, 1, 2); }
    } => ["expected a comparison"];
    assignment_is_no_comparison: {
        states { x } equations { der(x) = if(x = 1, 1, 2); }
    } => ["a condition compares with `<`, `<=`, `>`, `>=` or `==`, not `=`"];
    if_needs_two_values: {
        states { x } equations { der(x) = if(x > 0, 1); }
    } => ["`if` takes a condition and 2 values, `if(x > y, a, b)`, found 1 value(s)"];
    if_takes_no_more_than_two_values: {
        states { x } equations { der(x) = if(x > 0, 1, 2, 3); }
    } => ["found 3 value(s)"];
    if_is_written_as_a_function: {
        states { x } equations { der(x) = if x > 0 { 1 } else { 2 }; }
    } => ["`if` is written like a function: `if(x > y, a, b)`"];
    max_takes_two_arguments: {
        states { x } equations { der(x) = max(x); }
    } => ["`max` takes 2 arguments, found 1"];
    sign_takes_one_argument: {
        states { x } equations { der(x) = sign(x, 1); }
    } => ["`sign` takes 1 argument, found 2"];
    unknown_functions_list_the_new_ones: {
        states { x } equations { der(x) = clamp(x); }
    } => ["`atan2`, `hypot`, `sign`, `min`, `max`, `der` and `if(x > y, a, b)`"];
    names_in_conditions_are_resolved: {
        states { x } equations { der(x) = if(x > x0, 1, z); }
    } => ["unknown name `x0`", "unknown name `z`"];
    function_names_are_reserved: {
        states { x } let max = x; equations { der(x) = 1; }
    } => ["`max` is reserved: it is a function (built in)"];
}

#[test]
fn equality_is_refused_at_its_token() {
    let text = "mod m { states { x } equations { der(x) = if(x == 0, 1, 2); } }";
    let error = crate::Source::new("eq.dsl", text).compile().unwrap_err().0;
    assert_eq!(error.len(), 1, "{error:#?}");
    let at = text.find("==").unwrap();
    assert_eq!(
        (error[0].line, error[0].column, error[0].width),
        (1, at + 1, 2)
    );
}
