//! Variants through the whole compiler: each keeps the closure of what its quantities need.

use crate::common::model;
use model_algebra::{compile, CompileOptions};

#[test]
fn closure_over_solved_dependencies() {
    // der(a) reads b; der(b) reads c; der(c) reads nothing; d is independent.
    let spec = model(
        "mod m {
            params { k = 1 }
            states { a, b, c, d }
            equations { ea: der(a) = b; eb: der(b) = k*c; ec: der(c) = 1; ed: der(d) = d; }
            outputs { o = der(b); }
            variant only_a { keep { a } }
            variant only_o { keep { o } }
            variant only_d { keep { d } fix { k = 0 } }
        }",
    );
    let m = compile(&spec, &CompileOptions::default()).unwrap();
    let kept = |k: usize| &m.variants[k];
    assert_eq!(kept(0).states, vec!["a", "b", "c"]);
    assert_eq!(kept(1).states, vec!["b", "c"]);
    assert_eq!(kept(1).outputs, vec!["o"]);
    let d = kept(2);
    assert_eq!(d.states, vec!["d"]);
    assert!(d.params.is_empty());
}
