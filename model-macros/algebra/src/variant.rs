//! Reduced variants: only the states the kept quantities need, with some parameters fixed.
//!
//! Fixed parameters are substituted before the solve (by the lowering), so a term multiplied by
//! a parameter fixed at zero is gone before it can cost anything and can even split a coupled
//! block. The kept states are then closed over the solved dependencies: `der(y_i)` needs `y_j`
//! when its definition reads `y_j`, directly or through the derivatives it uses; an output
//! needs the states it reads, the derivatives it reads (their states are kept, so that `dy` has
//! them) and, transitively, what those need.

use std::collections::BTreeSet;

use crate::expr::Sym;
use crate::options::CompileOptions;
use crate::program::CompiledModel;
use crate::solved::{Selection, Solved};
use crate::spec::{Diagnostic, ModelSpec, VariantSpec};

/// Compiles one variant of `spec`.
pub fn compile_variant(
    spec: &ModelSpec,
    variant: &VariantSpec,
    options: &CompileOptions,
) -> Result<CompiledModel, Vec<Diagnostic>> {
    let mut diags = Vec::new();
    let mut fixed = vec![None; spec.params.len()];
    for f in &variant.fix {
        match spec.params.iter().position(|p| p.name == f.name) {
            Some(i) if f.value.is_finite() => fixed[i] = Some(f.value),
            Some(_) => diags.push(Diagnostic {
                id: f.id,
                message: format!("`{}` is fixed to {}, which is not finite", f.name, f.value),
            }),
            None => diags.push(Diagnostic {
                id: f.id,
                message: format!(
                    "variant `{}` fixes `{}`, which is not a parameter",
                    variant.name, f.name
                ),
            }),
        }
    }
    let mut kept_states = BTreeSet::new();
    let mut kept_outputs = BTreeSet::new();
    for k in &variant.keep {
        if let Some(i) = spec.states.iter().position(|s| s.name == k.name) {
            kept_states.insert(i);
        } else if let Some(i) = spec.outputs.iter().position(|o| o.name == k.name) {
            kept_outputs.insert(i);
        } else {
            diags.push(Diagnostic {
                id: k.id,
                message: format!(
                    "variant `{}` keeps `{}`, which is neither a state nor an output",
                    variant.name, k.name
                ),
            });
        }
    }
    if variant.keep.is_empty() {
        diags.push(Diagnostic {
            id: variant.id,
            message: format!("variant `{}` keeps nothing", variant.name),
        });
    }
    if !diags.is_empty() {
        return Err(diags);
    }
    let mut solved = Solved::build(spec, fixed, options).map_err(|ds| {
        ds.into_iter()
            .map(|d| Diagnostic {
                id: d.id,
                message: format!("in variant `{}`: {}", variant.name, d.message),
            })
            .collect::<Vec<_>>()
    })?;
    for &k in &kept_outputs {
        for s in solved.pool.symbols(solved.outputs[k]) {
            if let Sym::State(i) | Sym::Der(i) = s {
                kept_states.insert(i);
            }
        }
    }
    loop {
        let states: Vec<usize> = kept_states.iter().copied().collect();
        let before = kept_states.len();
        for s in solved.inputs_of_ders(&states) {
            if let Sym::State(i) = s {
                kept_states.insert(i);
            }
        }
        if kept_states.len() == before {
            break;
        }
    }
    let selection = Selection {
        states: kept_states.into_iter().collect(),
        outputs: kept_outputs.into_iter().collect(),
    };
    let explanation = crate::explain::explain(&solved, spec);
    let mut model = solved.emit(spec, &variant.name, &selection).map_err(|u| {
        vec![Diagnostic {
            id: variant.id,
            message: format!(
                "variant `{}`: the compiler lost track of {:?} (this is a bug)",
                variant.name, u.0
            ),
        }]
    })?;
    model.explanation = explanation;
    Ok(model)
}
