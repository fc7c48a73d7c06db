//! A compiled switched model as Rust: one module per mode (every item a smooth model has), and
//! around them the switched model itself, whose `SwitchedModel` implementation dispatches on
//! the mode and runs the guards and resets the compiler derived.
//!
//! The modes share the states, parameters and outputs, so the parent re-exports the first
//! mode's names for them (`State`, `Params`, `state::h`, ...) and adds the mode graph: what
//! each event does, as `model_runtime::ModeGraph` tables that `model_runtime::Switched` follows,
//! and what each mode's guards read (`guard_inputs`, from the guards' compiled program), so
//! that screening interpolates only those components.

use crate::emit::{emit, generated_allows};
use crate::emit_program::{constant, statements};
use model_dsl::{Action, CompiledSwitched, Crossing, Jump, ModelAst};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// Emits a switched model: its modes' modules and the switched `Model`. `modes` holds each
/// mode's model as written (names, docs), in the order of `compiled.modes`.
pub fn emit_switched(
    ast: &ModelAst,
    modes: &[&ModelAst],
    compiled: &CompiledSwitched,
) -> TokenStream {
    let vis = &ast.vis;
    let ident = &ast.name;
    let name = ident.to_string();
    let default_doc = format!(" The switched model `{name}`, each mode solved at compile time.");
    let docs = if ast.attrs.is_empty() {
        quote! { #[doc = #default_doc] }
    } else {
        let attrs = &ast.attrs;
        quote! { #(#attrs)* }
    };
    let mode_modules = modes.iter().zip(&compiled.modes).map(|(mode, compiled)| {
        let mut mode_ast = (*mode).clone();
        mode_ast.vis = syn::parse_quote!(pub);
        if mode_ast.attrs.is_empty() {
            let doc = format!(" Mode `{}` of `{name}`.", mode_ast.name);
            mode_ast.attrs = vec![syn::parse_quote!(#[doc = #doc])];
        }
        emit(&mode_ast, &compiled.model)
    });
    let first = format_ident!("{}", compiled.modes[0].model.name);
    let mode_idents: Vec<_> = (compiled.modes.iter())
        .map(|m| format_ident!("{}", m.model.name))
        .collect();
    let mode_names: Vec<&str> = compiled
        .modes
        .iter()
        .map(|m| m.model.name.as_str())
        .collect();
    let n_modes = mode_names.len();
    let mode_indices = 0..n_modes;
    let initial = compiled.initial.iter().map(|v| constant(v.unwrap_or(0.0)));
    // The discrete values follow the model's parameters in `params` (their initial values
    // are the defaults there): every mode's model reads them as parameters.
    let n_discrete = compiled.discrete.len();
    let n_params = compiled.n_params();
    let discrete_names: Vec<&str> = compiled.discrete.iter().map(|(n, _)| n.as_str()).collect();
    let discrete_consts = discrete_names.iter().enumerate().map(|(j, name)| {
        let ident = format_ident!("{}", name);
        let index = n_params + j;
        let doc = format!(" Index of discrete value `{name}` in [`Model::params`](super::Model).");
        quote! {
            #[doc = #doc]
            pub const #ident: usize = #index;
        }
    });
    let mode_params = quote! { self.params };
    let decls = compiled.modes.iter().map(|mode| {
        let mode_name = &mode.model.name;
        let events = mode.events.iter().map(|event| {
            let event_name = &event.name;
            let direction = match event.crossing {
                Crossing::Up => quote! { ::model_runtime::Direction::Up },
                Crossing::Down => quote! { ::model_runtime::Direction::Down },
                Crossing::Both => quote! { ::model_runtime::Direction::Both },
            };
            let action = match &event.action {
                Action::Record => quote! { ::model_runtime::EventAction::Record },
                Action::Stop => quote! { ::model_runtime::EventAction::Stop },
                Action::Jump(jump) if jump.choice.is_some() => {
                    quote! { ::model_runtime::EventAction::Decide }
                }
                Action::Jump(jump) => {
                    let to = option_index(jump.to);
                    let reset = assigns(jump);
                    quote! { ::model_runtime::EventAction::Reset { to: #to, reset: #reset } }
                }
            };
            let accumulation = match &event.accumulation {
                Some(jump) => {
                    let to = option_index(jump.to);
                    let reset = assigns(jump);
                    quote! {
                        ::core::option::Option::Some(::model_runtime::AccumulationAction { to: #to, reset: #reset })
                    }
                }
                None => quote! { ::core::option::Option::None },
            };
            quote! {
                ::model_runtime::EventDecl {
                    name: ::std::string::String::from(#event_name),
                    direction: #direction,
                    action: #action,
                    on_accumulation: #accumulation,
                }
            }
        });
        quote! {
            ::model_runtime::ModeDecl {
                name: ::std::string::String::from(#mode_name),
                events: ::std::vec![#(#events),*],
            }
        }
    });
    let rhs_arms = mode_idents.iter().enumerate().map(|(k, m)| {
        quote! { #k => ::model_runtime::Model::<N_STATES>::rhs(&#m::Model::new(#mode_params), t, y, dy), }
    });
    let jacobian_arms = mode_idents.iter().enumerate().map(|(k, m)| {
        quote! { #k => ::model_runtime::Model::<N_STATES>::jacobian(&#m::Model::new(#mode_params), t, y, jac), }
    });
    // Each mode's first step: the derivatives, then the declared number; one that is not
    // finite and positive (or a model that cannot be evaluated there) leaves the step to the
    // integrator.
    let first_step_arms = compiled.modes.iter().enumerate().filter_map(|(k, mode)| {
        let body = statements(&mode.first_step.as_ref()?.program);
        let m = &mode_idents[k];
        Some(quote! {
            #k => {
                let p = &#mode_params;
                let mut derivative = [0.0f64; N_STATES];
                ::model_runtime::Model::<N_STATES>::rhs(&#m::Model::new(*p), t, y, &mut derivative).ok()?;
                let dy = &derivative;
                let step = || -> ::core::result::Result<f64, ::model_runtime::EvalError> {
                    let mut values = [0.0f64; 1];
                    {
                        let out = &mut values;
                        #body
                    }
                    ::core::result::Result::Ok(values[0])
                };
                step().ok().filter(|h| h.is_finite() && *h > 0.0)
            }
        })
    });
    let guard_arms = compiled.modes.iter().enumerate().map(|(k, mode)| {
        let n = mode.events.len();
        let body = statements(&mode.guards);
        quote! {
            #k => {
                let out: &mut [f64] = &mut values[..#n];
                #body
            }
        }
    });
    // What each mode's guards read, from the guards' program: screening then interpolates
    // only those components of the dense output.
    let input_arms = compiled.modes.iter().enumerate().map(|(k, mode)| {
        let reads = mode.guards.reads();
        let (states, ders) = (reads.states, reads.ders);
        quote! { #k => ::model_runtime::GuardInputs::of(&[#(#states),*], &[#(#ders),*]), }
    });
    // Each mode's clock in regularised time (1 where none is declared). It reads only states
    // and parameters (checked by the compiler); a pivot it cannot divide by makes it NaN, which
    // the integrator reports as a derivative that is not finite.
    let clock_arms = compiled.modes.iter().enumerate().filter_map(|(k, mode)| {
        let body = statements(&mode.time_scale.as_ref()?.program);
        Some(quote! {
            #k => {
                let t = 0.0f64;
                let dy = &[0.0f64; N_STATES];
                let clock = || -> ::core::result::Result<f64, ::model_runtime::EvalError> {
                    let mut values = [0.0f64; 1];
                    {
                        let out = &mut values;
                        #body
                    }
                    ::core::result::Result::Ok(values[0])
                };
                clock().unwrap_or(f64::NAN)
            }
        })
    });
    let mut reset_arms = Vec::new();
    let mut decide_arms = Vec::new();
    let layout = Layout {
        states: compiled.states().len(),
        discrete: n_discrete,
        params: n_params,
    };
    for (k, mode) in compiled.modes.iter().enumerate() {
        for (e, event) in mode.events.iter().enumerate() {
            if let Action::Jump(jump) = &event.action {
                let name = format!("{}.{}", mode.model.name, event.name);
                match decide_arm(k, e, &name, jump, layout) {
                    Some(arm) => decide_arms.push(arm),
                    None => reset_arms.push(reset_arm(k, e, false, jump, layout)),
                }
            }
            if let Some(jump) = &event.accumulation {
                reset_arms.push(reset_arm(k, e, true, jump, layout));
            }
        }
    }
    let explanation = explanation(compiled);
    let defaults = compiled.modes[0]
        .model
        .params
        .iter()
        .all(|(_, d)| d.is_some());
    let default_impl = defaults.then(|| {
        quote! {
            impl ::core::default::Default for Model {
                /// The model with every parameter at the DSL's default.
                fn default() -> Self {
                    Model::from_params(Params::default())
                }
            }
        }
    });
    let allows = generated_allows();
    quote! {
        #docs
        #allows
        #vis mod #ident {
            #(#mode_modules)*
            pub use self::#first::{
                output, param, state, Outputs, Params, State, N_OUTPUTS, N_PARAMS, N_STATES,
                OUTPUT_NAMES, PARAM_DEFAULTS, PARAM_NAMES, STATE_NAMES,
            };
            /// The number of discrete values: numbers that hold between events, set only by
            /// events, kept at the end of [`Model::params`] (after the parameters proper; their
            /// defaults there are where a run starts).
            pub const N_DISCRETE: usize = #n_discrete;
            /// Index of each discrete value in [`Model::params`].
            pub mod discrete {
                #(#discrete_consts)*
            }
            /// Discrete value names, in index order.
            pub const DISCRETE_NAMES: [&str; N_DISCRETE] = [#(#discrete_names),*];
            /// What a Rust function of an event (`by FUNCTION`) writes: the states, then the
            /// discrete values.
            pub const N_VALUES: usize = N_STATES + N_DISCRETE;
            const MODEL_NAME: &str = #name;
            /// The number of modes.
            pub const N_MODES: usize = #n_modes;
            /// Mode names, in index order (the first is where a run starts).
            pub const MODE_NAMES: [&str; N_MODES] = [#(#mode_names),*];
            /// Index of each mode.
            pub mod mode {
                #(
                    #[doc = concat!(" Index of mode `", #mode_names, "`.")]
                    pub const #mode_idents: usize = #mode_indices;
                )*
            }
            /// The initial state written in the model (`0` where none is written).
            pub const INITIAL: [f64; N_STATES] = [#(#initial),*];
            /// The modes, their events and what each event does, then each mode's solved
            /// equations (Markdown).
            pub const SWITCHING_MARKDOWN: &str = #explanation;
            /// The switched model with its parameter values and its mode graph.
            #[derive(Clone, Debug, PartialEq)]
            pub struct Model {
                /// Parameter values, indexed by the constants of [`param`], then the discrete
                /// values as they are now (indexed by the constants of [`discrete`]).
                pub params: [f64; N_PARAMS],
                graph: ::model_runtime::ModeGraph,
            }
            impl Model {
                /// A model with these parameter values (indexed by the constants of [`param`]).
                pub fn new(params: [f64; N_PARAMS]) -> Self {
                    let graph = ::model_runtime::ModeGraph::new(::std::vec![#(#decls),*])
                        .expect("the mode graph was checked when the model was compiled");
                    Model { params, graph }
                }
                /// A model with these named parameter values.
                pub fn from_params(params: Params) -> Self {
                    Model::new(params.to_array())
                }
            }
            #default_impl
            impl ::model_runtime::SwitchedModel<::model_runtime::Const<N_STATES>> for Model {
                fn graph(&self) -> &::model_runtime::ModeGraph {
                    &self.graph
                }
                fn rhs(
                    &self,
                    mode: usize,
                    t: f64,
                    y: &[f64; N_STATES],
                    dy: &mut [f64; N_STATES],
                ) -> ::core::result::Result<(), ::model_runtime::EvalError> {
                    match mode {
                        #(#rhs_arms)*
                        _ => ::core::result::Result::Err(unknown_mode()),
                    }
                }
                fn jacobian(
                    &self,
                    mode: usize,
                    t: f64,
                    y: &[f64; N_STATES],
                    jac: &mut [[f64; N_STATES]; N_STATES],
                ) -> ::core::result::Result<(), ::model_runtime::EvalError> {
                    match mode {
                        #(#jacobian_arms)*
                        _ => ::core::result::Result::Err(unknown_mode()),
                    }
                }
                fn event_values(
                    &self,
                    mode: usize,
                    t: f64,
                    y: &[f64; N_STATES],
                    dy: &[f64; N_STATES],
                    values: &mut [f64],
                ) -> ::core::result::Result<(), ::model_runtime::EvalError> {
                    let p = &#mode_params;
                    match mode {
                        #(#guard_arms)*
                        _ => return ::core::result::Result::Err(unknown_mode()),
                    }
                    ::core::result::Result::Ok(())
                }
                fn guard_inputs(
                    &self,
                    mode: usize,
                ) -> ::core::option::Option<::model_runtime::GuardInputs<::model_runtime::Const<N_STATES>>> {
                    ::core::option::Option::Some(match mode {
                        #(#input_arms)*
                        _ => ::model_runtime::GuardInputs::ALL,
                    })
                }
                fn decide(
                    &mut self,
                    mode: usize,
                    event: usize,
                    t: f64,
                    y: &[f64; N_STATES],
                    dy: &[f64; N_STATES],
                    new: &mut [f64; N_STATES],
                ) -> ::core::result::Result<::core::option::Option<usize>, ::model_runtime::EvalError> {
                    let next: ::core::option::Option<usize> = match (mode, event) {
                        #(#decide_arms)*
                        _ => ::core::option::Option::None,
                    };
                    ::core::result::Result::Ok(next)
                }
                fn first_step(&self, mode: usize, t: f64, y: &[f64; N_STATES]) -> ::core::option::Option<f64> {
                    match mode {
                        #(#first_step_arms)*
                        _ => ::core::option::Option::None,
                    }
                }
                fn time_scale(&self, mode: usize, y: &[f64; N_STATES]) -> f64 {
                    let p = &#mode_params;
                    match mode {
                        #(#clock_arms)*
                        _ => 1.0,
                    }
                }
                fn reset(
                    &mut self,
                    mode: usize,
                    event: usize,
                    accumulation: bool,
                    t: f64,
                    y: &[f64; N_STATES],
                    dy: &[f64; N_STATES],
                    new: &mut [f64; N_STATES],
                ) -> ::core::result::Result<(), ::model_runtime::EvalError> {
                    let p = &#mode_params;
                    match (mode, event, accumulation) {
                        #(#reset_arms)*
                        _ => {}
                    }
                    ::core::result::Result::Ok(())
                }
            }
            /// A mode index outside the graph: reported as a non-finite derivative of no state.
            fn unknown_mode() -> ::model_runtime::EvalError {
                ::model_runtime::EvalError::non_finite(
                    MODEL_NAME,
                    "the mode index (out of range)",
                    f64::NAN,
                )
            }
        }
    }
}

fn option_index(index: Option<usize>) -> TokenStream {
    match index {
        Some(k) => quote! { ::core::option::Option::Some(#k) },
        None => quote! { ::core::option::Option::None },
    }
}

/// How many states and discrete values a reset may assign: a reset's slot `k` is state `k`
/// below `states`, discrete value `k - states` above (kept after the `params` parameters).
#[derive(Clone, Copy)]
struct Layout {
    states: usize,
    discrete: usize,
    params: usize,
}

/// The call of an event's Rust function with the values it may write: the new state alone,
/// or, when the model has discrete values, the states then the discrete values, copied back
/// only when the function succeeds.
fn rust_call(function: &str, layout: Layout) -> TokenStream {
    let function = format_ident!("{}", function);
    if layout.discrete == 0 {
        return quote! { super::#function(self, t, y, dy, new)? };
    }
    quote! {
        {
            let mut values = [0.0f64; N_VALUES];
            values[..N_STATES].copy_from_slice(&new[..]);
            values[N_STATES..].copy_from_slice(&self.params[N_PARAMS - N_DISCRETE..]);
            let result = super::#function(self, t, y, dy, &mut values)?;
            new.copy_from_slice(&values[..N_STATES]);
            self.params[N_PARAMS - N_DISCRETE..].copy_from_slice(&values[N_STATES..]);
            result
        }
    }
}

/// One arm of `decide`, for a jump whose Rust function also chooses the next mode: the call,
/// and the check that the mode it names is one the event lists (or a stop it allows).
fn decide_arm(
    mode: usize,
    event: usize,
    name: &str,
    jump: &Jump,
    layout: Layout,
) -> Option<TokenStream> {
    let choice = jump.choice.as_ref()?;
    let call = rust_call(jump.by.as_deref()?, layout);
    let modes = &choice.modes;
    let stop = choice.stop;
    Some(quote! {
        (#mode, #event) => match #call {
            ::core::option::Option::Some(next) if [#(#modes),*].contains(&next) => {
                ::core::option::Option::Some(next)
            }
            ::core::option::Option::None if #stop => ::core::option::Option::None,
            other => {
                return ::core::result::Result::Err(::model_runtime::EvalError::Undecided {
                    event: ::std::string::String::from(#name),
                    mode: other,
                })
            }
        },
    })
}

/// Whether a jump assigns states: written resets, or a Rust function's.
fn assigns(jump: &Jump) -> bool {
    !jump.states.is_empty() || jump.by.is_some()
}

/// One arm of `reset`: the program of the new values into a local array, then each into its
/// state; or a call of the Rust function that computes the new state (`by FUNCTION`), which
/// the model's module finds in the module around it.
fn reset_arm(
    mode: usize,
    event: usize,
    accumulation: bool,
    jump: &Jump,
    layout: Layout,
) -> TokenStream {
    if let Some(function) = &jump.by {
        let call = rust_call(function, layout);
        return quote! {
            (#mode, #event, #accumulation) => #call,
        };
    }
    let n = jump.states.len();
    let body = statements(&jump.program);
    let targets = jump.states.iter().enumerate().map(|(k, &s)| {
        if s < layout.states {
            quote! { new[#s] = values[#k]; }
        } else {
            let d = layout.params + s - layout.states;
            quote! { self.params[#d] = values[#k]; }
        }
    });
    quote! {
        (#mode, #event, #accumulation) => {
            let mut values = [0.0f64; #n];
            {
                let out = &mut values;
                #body
            }
            #(#targets)*
        }
    }
}

/// The modes and events as Markdown, then each mode's solved equations.
fn explanation(compiled: &CompiledSwitched) -> String {
    let mut text = model_dsl::switching_markdown(compiled);
    for mode in &compiled.modes {
        text.push('\n');
        text.push_str(&mode.model.explanation.markdown);
    }
    text
}
