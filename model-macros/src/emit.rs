//! The compiled model as Rust items: the module, its constants, `INFO`, the `Model` type and its
//! trait implementations, and one nested module per variant.
//!
//! Everything the user can name is documented, so a crate with `#![deny(missing_docs)]` accepts
//! the expansion, and the lints that generated straight-line code trips are allowed on the module.

use crate::emit_named::{named_items, ItemDocs};
use crate::emit_program::{constant, statements, zero_unstored};
use model_algebra::{CompiledModel, Program, Target};
use model_dsl::ModelAst;
use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

/// Emits the whole expansion of a compiled model.
pub fn emit(ast: &ModelAst, compiled: &CompiledModel) -> TokenStream {
    let name = ast.name.to_string();
    let default_doc = format!(" The `{name}` model, solved for its derivatives at compile time.");
    let docs = docs_or(&ast.attrs, &default_doc);
    if compiled.variants.len() != ast.variants.len() {
        let message = format!(
            "the equation compiler returned {} variants for the {} declared",
            compiled.variants.len(),
            ast.variants.len()
        );
        return syn::Error::new(ast.name.span(), message).to_compile_error();
    }
    let variants = ast
        .variants
        .iter()
        .zip(&compiled.variants)
        .map(|(variant, model)| {
            let default_doc = format!(" A reduced variant of `{name}`.");
            let header = Header {
                vis: syn::parse_quote!(pub),
                ident: &variant.name,
                docs: docs_or(&variant.attrs, &default_doc),
                info_name: format!("{name}::{}", variant.name),
                item_docs: &ast.docs,
            };
            module(&header, model, TokenStream::new())
        });
    let variants: TokenStream = variants.collect();
    let header = Header {
        vis: ast.vis.clone(),
        ident: &ast.name,
        docs,
        info_name: name.clone(),
        item_docs: &ast.docs,
    };
    module(&header, compiled, variants)
}

/// What names and documents an emitted module, beside the compiled model itself.
struct Header<'a> {
    vis: syn::Visibility,
    ident: &'a Ident,
    docs: TokenStream,
    /// `INFO.name` and the `model` of every runtime error.
    info_name: String,
    item_docs: &'a ItemDocs,
}

/// The lints that generated straight-line code trips, allowed on every emitted module.
pub fn generated_allows() -> TokenStream {
    quote! {
        #[allow(
            non_upper_case_globals,
            non_snake_case,
            unused_variables,
            unused_parens,
            clippy::all,
            clippy::pedantic,
            clippy::nursery
        )]
    }
}

/// The doc attributes written by the user, or one default line.
fn docs_or(attrs: &[syn::Attribute], default: &str) -> TokenStream {
    if attrs.is_empty() {
        quote! { #[doc = #default] }
    } else {
        quote! { #(#attrs)* }
    }
}

fn module(header: &Header, model: &CompiledModel, nested: TokenStream) -> TokenStream {
    let Header {
        vis,
        ident,
        docs,
        info_name,
        item_docs,
    } = header;
    let info_name = info_name.as_str();
    let n_states = model.states.len();
    let n_params = model.params.len();
    let n_outputs = model.outputs.len();
    let param_names: Vec<&str> = model.params.iter().map(|(name, _)| name.as_str()).collect();
    let state_refs: Vec<&str> = model.states.iter().map(String::as_str).collect();
    let output_refs: Vec<&str> = model.outputs.iter().map(String::as_str).collect();
    let states = index_module("state", "state", &state_refs, item_docs);
    let params = index_module("param", "parameter", &param_names, item_docs);
    let outputs = index_module("output", "output", &output_refs, item_docs);
    let state_names = &model.states;
    let output_names = &model.outputs;
    let defaults = model.params.iter().map(|(_, default)| match default {
        Some(value) => {
            let value = constant(*value);
            quote! { ::core::option::Option::Some(#value) }
        }
        None => quote! { ::core::option::Option::None },
    });
    let initial =
        (0..n_states).map(|k| constant(model.initial.get(k).copied().flatten().unwrap_or(0.0)));
    let info = info(info_name, model);
    let solved_markdown = &model.explanation.markdown;
    let solved_latex = &model.explanation.latex;
    let default_values = default_values(model);
    let default_impl = default_impl(default_values.as_deref());
    let named = named_items(
        &param_names,
        default_values.as_deref(),
        &state_refs,
        &output_refs,
        item_docs,
    );
    let model_impl = model_impl(model);
    let outputs_impl = outputs_impl(model);
    let allows = generated_allows();
    quote! {
        #docs
        #allows
        #vis mod #ident {
            /// The number of states.
            pub const N_STATES: usize = #n_states;
            /// The number of parameters.
            pub const N_PARAMS: usize = #n_params;
            /// The number of outputs.
            pub const N_OUTPUTS: usize = #n_outputs;
            #states
            #params
            #outputs
            /// State names, in index order.
            pub const STATE_NAMES: [&str; N_STATES] = [#(#state_names),*];
            /// Parameter names, in index order.
            pub const PARAM_NAMES: [&str; N_PARAMS] = [#(#param_names),*];
            /// Output names, in index order.
            pub const OUTPUT_NAMES: [&str; N_OUTPUTS] = [#(#output_names),*];
            /// Parameter defaults (`None` where the model gives none), in index order.
            pub const PARAM_DEFAULTS: [::core::option::Option<f64>; N_PARAMS] = [#(#defaults),*];
            /// The initial state written in the model (`states { x = 2 }`; `0` where none is
            /// written): where a run starts unless told otherwise.
            pub const INITIAL: [f64; N_STATES] = [#(#initial),*];
            const MODEL_NAME: &str = #info_name;
            /// The solved equations as the compiler derived them, block by block with their
            /// pivots, then the outputs (Markdown, DSL syntax).
            pub const SOLVED_MARKDOWN: &str = #solved_markdown;
            /// The same equations as a LaTeX `align*` environment.
            pub const SOLVED_LATEX: &str = #solved_latex;
            #info
            /// The model with its parameter values.
            #[derive(Clone, Debug, PartialEq)]
            pub struct Model {
                /// Parameter values, indexed by the constants of [`param`].
                pub params: [f64; N_PARAMS],
            }
            impl Model {
                /// A model with these parameter values (indexed by the constants of [`param`]).
                pub const fn new(params: [f64; N_PARAMS]) -> Self {
                    Model { params }
                }
            }
            #default_impl
            #named
            #model_impl
            #outputs_impl
            #nested
        }
    }
}

/// `pub mod NAME { pub const x: usize = 0; ... }`, each constant documented by the user's doc
/// comment on the name, or by a default line.
fn index_module(module: &str, what: &str, names: &[&str], item_docs: &ItemDocs) -> TokenStream {
    let module = Ident::new(module, Span::call_site());
    let module_doc = format!(" Index of each {what} in the {what} array.");
    let consts = names.iter().enumerate().map(|(index, name)| {
        let ident = format_ident!("{}", name);
        let default = format!(" Index of {what} `{name}`.");
        let docs = docs_or(item_docs.get(*name).map_or(&[], Vec::as_slice), &default);
        quote! {
            #docs
            pub const #ident: usize = #index;
        }
    });
    quote! {
        #[doc = #module_doc]
        pub mod #module {
            #(#consts)*
        }
    }
}

fn info(info_name: &str, model: &CompiledModel) -> TokenStream {
    let rhs_ops = ops(&model.rhs);
    let jacobian_ops = ops(&model.jacobian);
    let outputs_ops = ops(&model.outputs_program);
    let pivots = &model.pivots;
    let blocks = &model.numeric_blocks;
    quote! {
        /// Names, sizes, operation counts, checked pivots and numerically solved blocks.
        pub static INFO: ::model_runtime::ModelInfo = ::model_runtime::ModelInfo {
            name: ::model_runtime::Name::Borrowed(#info_name),
            state_names: ::model_runtime::Names::Static(&STATE_NAMES),
            param_names: ::model_runtime::Names::Static(&PARAM_NAMES),
            output_names: ::model_runtime::Names::Static(&OUTPUT_NAMES),
            rhs_ops: #rhs_ops,
            jacobian_ops: #jacobian_ops,
            outputs_ops: #outputs_ops,
            pivots: ::model_runtime::Names::Static(&[#(#pivots),*]),
            numeric_blocks: ::model_runtime::Names::Static(&[#(#blocks),*]),
        };
    }
}

fn ops(program: &Program) -> TokenStream {
    let ops = program.ops();
    let (add, mul, div) = (ops.add, ops.mul, ops.div);
    let (sqrt, trig, transcendental) = (ops.sqrt, ops.trig, ops.transcendental);
    quote! {
        ::model_runtime::OpCounts {
            add: #add, mul: #mul, div: #div, sqrt: #sqrt, trig: #trig, transcendental: #transcendental,
        }
    }
}

/// Every parameter's default as a literal, when every parameter has one.
fn default_values(model: &CompiledModel) -> Option<Vec<TokenStream>> {
    model
        .params
        .iter()
        .map(|(_, default)| default.map(constant))
        .collect()
}

fn default_impl(values: Option<&[TokenStream]>) -> TokenStream {
    let Some(values) = values else {
        return TokenStream::new();
    };
    quote! {
        /// Every parameter at its default.
        impl ::core::default::Default for Model {
            fn default() -> Self {
                Model::new([#(#values),*])
            }
        }
    }
}

fn model_impl(model: &CompiledModel) -> TokenStream {
    let n = model.states.len();
    let der_names = model.states.iter().map(|state| format!("der({state})"));
    let jac_names = model.states.iter().map(|row| {
        let row = model
            .states
            .iter()
            .map(|col| format!("jacobian entry d der({row}) / d {col}"));
        quote! { [#(#row),*] }
    });
    let rhs = statements(&model.rhs);
    let rhs_zero = zero_unstored(&model.rhs, (0..n).map(Target::Der));
    let jacobian = statements(&model.jacobian);
    let jac_zero = zero_unstored(
        &model.jacobian,
        (0..n).flat_map(|i| (0..n).map(move |j| Target::Jac(i, j))),
    );
    quote! {
        const DER_NAMES: [&str; N_STATES] = [#(#der_names),*];
        const JACOBIAN_NAMES: [[&str; N_STATES]; N_STATES] = [#(#jac_names),*];
        impl ::model_runtime::Model<N_STATES> for Model {
            #[inline]
            fn info(&self) -> &'static ::model_runtime::ModelInfo {
                &INFO
            }

            fn rhs(
                &self,
                t: f64,
                y: &[f64; N_STATES],
                dy: &mut [f64; N_STATES],
            ) -> ::core::result::Result<(), ::model_runtime::EvalError> {
                let p = &self.params;
                #rhs_zero
                #rhs
                ::model_runtime::check_finite(MODEL_NAME, &DER_NAMES, dy)
            }

            fn jacobian(
                &self,
                t: f64,
                y: &[f64; N_STATES],
                jac: &mut [[f64; N_STATES]; N_STATES],
            ) -> ::core::result::Result<(), ::model_runtime::EvalError> {
                let p = &self.params;
                #jac_zero
                #jacobian
                ::model_runtime::check_finite(
                    MODEL_NAME,
                    JACOBIAN_NAMES.as_flattened(),
                    jac.as_flattened(),
                )
            }
        }
    }
}

fn outputs_impl(model: &CompiledModel) -> TokenStream {
    let program = &model.outputs_program;
    let body = statements(program);
    let zero = zero_unstored(program, (0..model.outputs.len()).map(Target::Output));
    quote! {
        impl ::model_runtime::WithOutputs<N_STATES, N_OUTPUTS> for Model {
            fn outputs(
                &self,
                t: f64,
                y: &[f64; N_STATES],
                dy: &[f64; N_STATES],
                out: &mut [f64; N_OUTPUTS],
            ) -> ::core::result::Result<(), ::model_runtime::EvalError> {
                let p = &self.params;
                #zero
                #body
                ::model_runtime::check_finite(MODEL_NAME, &OUTPUT_NAMES, out)
            }
        }
    }
}
