//! The front end never panics, whatever tokens it is given: random token soups and random
//! mutations of a valid model go through parse and validate, which must return `Ok` or a
//! diagnostic; mutated models also go through the whole expansion, compiler included.

use crate::expand::expand_timed;
use model_dsl::{parse_model, validate};
use proc_macro2::TokenStream;
use proptest::prelude::*;

const VALID: &str = "
    /// A pendulum.
    pub mod pend {
        params { m = 1.0, l = 1.0, g = 9.81 }
        states { phi, omega }
        let x = l * sin(phi);
        let y = -l * cos(phi);
        equations {
            kinematics: der(phi) = omega;
            balance: m * l^2 * der(omega) = -m * g * x;
        }
        outputs {
            energy = m / 2 * (l * omega)^2 + m * g * y;
            power = der(energy) * 0 + m * l^2 * omega * der(omega);
            side = if(phi >= 0, max(x, y), sign(omega) * min(x, der(omega)));
        }
        variant small { keep { omega } fix { m = 1 } }
        chart scaled { states { w } replace { omega } let omega = 2*w; }
    }
";

/// Tokens the soups are made of: every keyword, operator and delimiter of the DSL.
const ALPHABET: &[&str] = &[
    "mod",
    "pub",
    "m",
    "params",
    "states",
    "let",
    "equations",
    "outputs",
    "variant",
    "keep",
    "fix",
    "chart",
    "replace",
    "after",
    "der",
    "sin",
    "atan2",
    "hypot",
    "sign",
    "min",
    "max",
    "if",
    "t",
    "pi",
    "x",
    "y",
    "k",
    "{",
    "}",
    "(",
    ")",
    "=",
    ";",
    ":",
    ",",
    "+",
    "-",
    "*",
    "/",
    "^",
    "1",
    "2.5",
    "1e-3",
    "0",
    "///",
    "#",
    "[",
    "]",
    "::",
    "==",
    "<",
    ">=",
    "-1",
];

fn check(text: &str) {
    // Unbalanced delimiters cannot even be tokens; the compiler never hands those to a macro.
    let Ok(tokens) = text.parse::<TokenStream>() else {
        return;
    };
    if let Ok(ast) = parse_model(tokens) {
        let _ = validate(&ast);
    }
}

fn valid_words() -> Vec<String> {
    VALID.split_whitespace().map(str::to_string).collect()
}

/// One random edit of a word list.
#[derive(Clone, Debug)]
enum Edit {
    Delete(usize),
    Duplicate(usize),
    Swap(usize, usize),
    Insert(usize, usize),
}

fn apply(words: &mut Vec<String>, edit: &Edit) {
    let n = words.len();
    match *edit {
        Edit::Delete(i) => {
            words.remove(i % n);
        }
        Edit::Duplicate(i) => words.insert(i % n, words[i % n].clone()),
        Edit::Swap(i, j) => words.swap(i % n, j % n),
        Edit::Insert(i, token) => words.insert(i % n, ALPHABET[token % ALPHABET.len()].to_string()),
    }
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        any::<usize>().prop_map(Edit::Delete),
        any::<usize>().prop_map(Edit::Duplicate),
        (any::<usize>(), any::<usize>()).prop_map(|(i, j)| Edit::Swap(i, j)),
        (any::<usize>(), any::<usize>()).prop_map(|(i, t)| Edit::Insert(i, t)),
    ]
}

#[test]
fn the_valid_model_is_valid() {
    let ast = parse_model(VALID.parse().unwrap()).unwrap();
    validate(&ast).unwrap();
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn token_soups_never_panic(words in prop::collection::vec(0..ALPHABET.len(), 0..60)) {
        let text: Vec<&str> = words.iter().map(|&i| ALPHABET[i]).collect();
        check(&format!("mod m {{ {} }}", text.join(" ")));
        check(&text.join(" "));
    }

    #[test]
    fn mutated_models_never_panic(edits in prop::collection::vec(edit(), 1..6)) {
        let mut words = valid_words();
        for edit in &edits {
            if words.is_empty() {
                break;
            }
            apply(&mut words, edit);
        }
        check(&words.join(" "));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn mutated_models_expand_without_panicking(edits in prop::collection::vec(edit(), 1..4)) {
        let mut words = valid_words();
        for edit in &edits {
            if words.is_empty() {
                break;
            }
            apply(&mut words, edit);
        }
        if let Ok(tokens) = words.join(" ").parse::<TokenStream>() {
            let (output, _) = expand_timed(tokens);
            // Whatever happened, the output is valid Rust (items and/or `compile_error!`s).
            prop_assert!(syn::parse2::<syn::File>(output).is_ok());
        }
    }
}
