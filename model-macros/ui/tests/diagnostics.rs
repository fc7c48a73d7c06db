//! Every diagnostic of the macro, one file each, with the exact message and the token it points
//! at (`TRYBUILD=overwrite` regenerates the `.stderr` files; read them before committing); and
//! expansions that must compile and run cleanly under strict lints.

#[test]
fn diagnostics() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/ui/*.rs");
    cases.pass("tests/pass/*.rs");
}
