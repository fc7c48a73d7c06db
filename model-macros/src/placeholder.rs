//! What is emitted in place of a model with errors: the same module with the same public items
//! (constants, index modules, `Model`, `new`, `Default`, the named structs, the trait
//! implementations, one module per variant), built from whatever names parsed, with empty
//! bodies.
//!
//! It exists so that the user sees the model's own errors and nothing else: code that uses
//! `m::Model::default()`, `m::state::x` or `m::Params { .. }` still type-checks against the
//! placeholder, and the bodies never run, because the crate does not compile. It is produced
//! by the same emitter as a real model, from a compiled model whose programs are empty, so its
//! items cannot drift from the real ones.

use crate::emit::emit;
use crate::emit_switched::emit_switched;
use model_algebra::Explanation;
use model_algebra::{CompiledModel, Program};
use model_dsl::{is_rust_keyword, CompiledMode, CompiledSwitched, ModelAst, RESERVED_MODULES};
use proc_macro2::TokenStream;
use std::collections::BTreeSet;

/// The placeholder module for a model that failed to parse, validate or compile.
pub fn placeholder(ast: &ModelAst) -> TokenStream {
    let mut ast = ast.clone();
    ast.attrs.retain(|attr| attr.path().is_ident("doc"));
    let mut variant_names = BTreeSet::new();
    ast.variants.retain(|variant| {
        let name = variant.name.to_string();
        !RESERVED_MODULES.contains(&name.as_str()) && variant_names.insert(name)
    });
    for variant in &mut ast.variants {
        variant.attrs.retain(|attr| attr.path().is_ident("doc"));
    }
    let stub = stub(&ast);
    emit(&ast, &stub)
}

/// The placeholder of a switched model: the same items as a real one (the modes' modules, the
/// mode indices, `INITIAL`, `Model` implementing `SwitchedModel`), with modes that have no
/// events and bodies that compute nothing.
pub fn switched_placeholder(ast: &ModelAst) -> TokenStream {
    let mut ast = ast.clone();
    ast.attrs.retain(|attr| attr.path().is_ident("doc"));
    ast.variants.clear();
    ast.charts.clear();
    let mut names = BTreeSet::new();
    let mut modes: Vec<ModelAst> = Vec::new();
    let written: Vec<(syn::Ident, Vec<syn::Attribute>)> = if ast.modes.is_empty() {
        vec![(ast.name.clone(), Vec::new())]
    } else {
        (ast.modes.iter())
            .map(|mode| (mode.name.clone(), mode.attrs.clone()))
            .collect()
    };
    for (name, mut attrs) in written {
        let text = name.to_string();
        let reserved =
            RESERVED_MODULES.contains(&text.as_str()) || text == "mode" || text == "stop";
        if reserved || !names.insert(text) {
            continue;
        }
        attrs.retain(|attr| attr.path().is_ident("doc"));
        let mut mode = ast.clone();
        mode.name = name;
        mode.attrs = attrs;
        mode.modes.clear();
        mode.events.clear();
        mode.accumulations.clear();
        modes.push(mode);
    }
    if modes.is_empty() {
        let mut mode = ast.clone();
        mode.name = syn::Ident::new("placeholder_mode", ast.name.span());
        modes.push(mode);
    }
    let stub = stub(&ast);
    let initial = (stub.states.iter())
        .map(|s| ast.initial.iter().find(|i| &i.name == s).map(|i| i.value))
        .collect();
    let compiled = CompiledSwitched {
        name: ast.name.to_string(),
        initial,
        discrete: Vec::new(),
        warnings: Vec::new(),
        modes: (modes.iter())
            .map(|mode| {
                let mut model = stub.clone();
                model.name = mode.name.to_string();
                CompiledMode {
                    model,
                    guards: Program::default(),
                    events: Vec::new(),
                    time_scale: None,
                    first_step: None,
                }
            })
            .collect(),
    };
    let refs: Vec<&ModelAst> = modes.iter().collect();
    emit_switched(&ast, &refs, &compiled)
}

/// A compiled model with the declared names (each once) and no code.
fn stub(ast: &ModelAst) -> CompiledModel {
    let states = unique(ast.states.iter().map(|s| (s.name.clone(), ())));
    let params = unique(ast.params.iter().map(|p| (p.name.clone(), p.value)));
    let outputs = unique(ast.outputs.iter().map(|o| (o.name.clone(), ())));
    let model = |name: String, params: Vec<(String, Option<f64>)>| CompiledModel {
        name,
        states: states.iter().map(|(name, ())| name.clone()).collect(),
        params,
        outputs: outputs.iter().map(|(name, ())| name.clone()).collect(),
        rhs: Program::default(),
        jacobian: Program::default(),
        outputs_program: Program::default(),
        pivots: Vec::new(),
        numeric_blocks: Vec::new(),
        variants: Vec::new(),
        explanation: Explanation::default(),
        initial: (states.iter())
            .map(|(name, ())| {
                ast.initial
                    .iter()
                    .find(|i| &i.name == name)
                    .map(|i| i.value)
            })
            .collect(),
    };
    let variants = ast
        .variants
        .iter()
        .map(|variant| {
            let fixed: BTreeSet<&str> = variant.fix.iter().map(|f| f.name.as_str()).collect();
            let kept = params
                .iter()
                .filter(|(name, _)| !fixed.contains(name.as_str()))
                .cloned()
                .collect();
            model(variant.name.to_string(), kept)
        })
        .collect();
    let mut compiled = model(ast.name.to_string(), params.clone());
    compiled.variants = variants;
    compiled
}

/// The first declaration of each name, in order (a name declared twice is already an error);
/// a Rust keyword (already an error) is left out, since no Rust item can be named by it.
fn unique<T>(items: impl Iterator<Item = (String, T)>) -> Vec<(String, T)> {
    let mut seen = BTreeSet::new();
    items
        .filter(|(name, _)| !is_rust_keyword(name) && seen.insert(name.clone()))
        .collect()
}
