//! The pipeline: the model solved once, emitted whole with its printed explanation, then each
//! reduced variant solved and emitted from its own parameters.

use crate::cse::Unbound;
use crate::explain::explain;
use crate::options::CompileOptions;
use crate::program::CompiledModel;
use crate::solved::{Selection, Solved};
use crate::spec::{Diagnostic, ModelSpec, NodeId};
use crate::variant::compile_variant;

/// Compiles a model and its variants.
pub fn compile(
    spec: &ModelSpec,
    options: &CompileOptions,
) -> Result<CompiledModel, Vec<Diagnostic>> {
    let mut solved = Solved::build(spec, vec![None; spec.params.len()], options)?;
    let everything = Selection {
        states: (0..spec.states.len()).collect(),
        outputs: (0..spec.outputs.len()).collect(),
    };
    // Printed before the emission adds the Jacobian's definitions to the system.
    let explanation = explain(&solved, spec);
    let mut model = solved
        .emit(spec, &spec.name, &everything)
        .map_err(|u| vec![unbound(spec, u)])?;
    model.explanation = explanation;
    let mut diags = Vec::new();
    for v in &spec.variants {
        match compile_variant(spec, v, options) {
            Ok(m) => model.variants.push(m),
            Err(d) => diags.extend(d),
        }
    }
    if diags.is_empty() {
        Ok(model)
    } else {
        Err(diags)
    }
}

fn unbound(spec: &ModelSpec, u: Unbound) -> Diagnostic {
    Diagnostic {
        id: spec.states.first().map_or(NodeId(0), |s| s.id),
        message: format!("the compiler lost track of {:?} (this is a bug)", u.0),
    }
}
