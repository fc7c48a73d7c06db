use super::show;
use crate::parse::parse_model;
use quote::quote;

/// Parses `let e = <expr>;` inside a minimal model and shows the expression.
fn parsed(expr: proc_macro2::TokenStream) -> String {
    let model = parse_model(quote! {
        mod m { states { x } let e = #expr; equations { der(x) = 0; } }
    })
    .expect("the test model parses");
    show(&model.lets[0].value)
}

macro_rules! precedence {
    ($($name:ident: ($($expr:tt)*) => $expected:literal;)*) => {$(
        #[test]
        fn $name() {
            assert_eq!(parsed(quote!($($expr)*)), $expected);
        }
    )*};
}

precedence! {
    sum_is_left_associative: (a - b - c) => "((a-b)-c)";
    product_is_left_associative: (a / b * c) => "((a/b)*c)";
    product_binds_tighter_than_sum: (a + b * c) => "(a+(b*c))";
    power_binds_tighter_than_unary_minus: (-x^2) => "(-(x^2))";
    power_is_right_associative: (a^b^c) => "(a^(b^c))";
    exponent_may_be_negated: (2^-x) => "(2^(-x))";
    unary_minus_binds_tighter_than_product: (-a * b) => "((-a)*b)";
    parentheses_group: ((a + b) * c) => "((a+b)*c)";
    power_of_a_call: (sin(x)^2 * l) => "((sin(x)^2)*l)";
    double_negation: (- -a) => "(-(-a))";
    calls_take_expressions: (atan2(y - 1, x * 2)) => "atan2((y-1),(x*2))";
    float_literals: (1e-3 * 0.5 + 2) => "((0.001*0.5)+2)";
}

#[test]
fn sections_and_defaults_are_read() {
    let model = parse_model(quote! {
        /// The docs.
        pub mod pend {
            params { m = 1.0, /// The rod's length.
                l, g = -9.81, }
            states { /// The angle from the vertical.
                phi, omega }
            let x = l * sin(phi);
            equations {
                kin: der(phi) = omega;
                der(omega) = -g / l * sin(phi);
            }
            outputs { /// The energy.
                e = m * x; }
            /// A variant.
            variant small { keep { omega } fix { m = 2 } }
        }
    })
    .unwrap();
    assert_eq!(model.name, "pend");
    assert_eq!(model.attrs.len(), 1);
    let params: Vec<_> = model
        .params
        .iter()
        .map(|p| (p.name.as_str(), p.value))
        .collect();
    assert_eq!(params, [("m", Some(1.0)), ("l", None), ("g", Some(-9.81))]);
    assert_eq!(model.states.len(), 2);
    assert_eq!(model.equations.len(), 2);
    assert_eq!(model.equations[0].label.as_ref().unwrap().name, "kin");
    assert!(model.equations[1].label.is_none());
    assert_eq!(model.outputs[0].name, "e");
    let documented: Vec<&str> = model.docs.keys().map(String::as_str).collect();
    assert_eq!(documented, ["e", "l", "phi"]);
    let variant = &model.variants[0];
    assert_eq!(
        (variant.name.to_string(), variant.attrs.len()),
        ("small".into(), 1)
    );
    assert_eq!(variant.fix[0].value, 2.0);
}

#[test]
fn syntax_errors_in_several_statements_are_all_reported() {
    let error = parse_model(quote! {
        mod m {
            states { x, y }
            equations {
                a: der(x) = * y;
                b: der(y) = x +;
            }
            outputs { o = x x; }
        }
    })
    .unwrap_err();
    let messages = super::messages(error);
    assert_eq!(messages.len(), 3, "{messages:?}");
}

#[test]
fn number_suffixes_are_rejected() {
    let error = parse_model(quote! { mod m { params { a = 1f32 } } }).unwrap_err();
    assert!(
        error.to_string().contains("suffixes are not allowed"),
        "{error}"
    );
}

#[test]
fn tokens_after_the_module_are_rejected() {
    let error = parse_model(quote! { mod m { } mod n { } }).unwrap_err();
    assert!(error.to_string().contains("exactly one module"), "{error}");
}
