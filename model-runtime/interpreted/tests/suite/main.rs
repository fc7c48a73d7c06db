//! The library's tests: smooth models against the same model compiled by `model!` and against
//! closed forms, switched models against closed forms, and every input error located.

mod as_written;
mod backward;
mod engine;
mod guards;
mod hypot;
mod oracle;
mod requests;
mod sizes;
mod smooth;
mod stepping;
mod switched;

use model_interpreted::{ModelFile, ModelRef, SolveRequest};

/// The file's text compiled (it must compile).
pub fn compile(name: &str, text: &str) -> ModelFile {
    ModelFile::from_text(name, text).unwrap_or_else(|err| panic!("{name}: {err}"))
}

/// The file's model itself.
pub fn model(file: &ModelFile) -> ModelRef<'_> {
    file.model(None).unwrap()
}

/// `request` with tight tolerances.
pub fn tight(mut request: SolveRequest) -> SolveRequest {
    request.rtol = 1e-12;
    request.atol = 1e-14;
    request
}

/// `x' = v, v' = -w^2 x`, with outputs equal to `v` and `x`.
pub const OSCILLATOR: &str = "mod oscillator {
    params { w = 3 }
    states { x, v }
    equations { der(x) = v; der(v) = -w^2 * x; }
    outputs { speed = v; position = x; }
}";
