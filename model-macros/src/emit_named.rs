//! The named forms beside the fast arrays: `Params` (with the DSL's defaults as `Default`),
//! `State` (a named view of a state vector, also used for derivatives) and `Outputs`.
//!
//! The arrays stay the interface of the integrators (fixed size, indexable, no allocation);
//! the structs are how a person writes and reads values, `Params { m: 0.5,
//! ..Default::default() }` instead of remembering that `m` is index 0. Conversions are plain
//! field copies, `const` where Rust allows it, so nothing in the hot loop changes.

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};
use std::collections::BTreeMap;

/// Doc comments written on parameters, states and outputs, by name.
pub type ItemDocs = BTreeMap<String, Vec<syn::Attribute>>;

/// One named struct: its type name, the index module its fields follow, the array length
/// constant, and what a field is called in its doc line.
struct Shape<'a> {
    ty: &'static str,
    index: &'static str,
    len: &'static str,
    what: &'static str,
    doc: &'static str,
    names: &'a [&'a str],
}

/// `Params`, `State` and `Outputs` with their conversions, and `Model`'s named constructors.
pub fn named_items(
    params: &[&str],
    defaults: Option<&[TokenStream]>,
    states: &[&str],
    outputs: &[&str],
    docs: &ItemDocs,
) -> TokenStream {
    let params_struct = shape(
        &Shape {
            ty: "Params",
            index: "param",
            len: "N_PARAMS",
            what: "parameter",
            doc: " The parameters by name; `to_array` gives the form [`Model::new`] takes.",
            names: params,
        },
        docs,
    );
    let state_struct = shape(
        &Shape {
            ty: "State",
            index: "state",
            len: "N_STATES",
            what: "state",
            doc: " A state vector (or its derivative) by name: a view of the array the integrators use.",
            names: states,
        },
        docs,
    );
    let outputs_struct = shape(
        &Shape {
            ty: "Outputs",
            index: "output",
            len: "N_OUTPUTS",
            what: "output",
            doc: " The outputs by name.",
            names: outputs,
        },
        docs,
    );
    let default_params = defaults.map(|values| {
        let fields = params.iter().map(|name| format_ident!("{}", name));
        quote! {
            /// Every parameter at the default the model gives it.
            impl ::core::default::Default for Params {
                fn default() -> Self {
                    Params { #(#fields: #values),* }
                }
            }
        }
    });
    quote! {
        #params_struct
        #default_params
        #state_struct
        #outputs_struct
        impl Model {
            /// A model with these named parameter values.
            pub const fn from_params(params: Params) -> Self {
                Model::new(params.to_array())
            }

            /// This model's parameter values by name.
            pub const fn named_params(&self) -> Params {
                Params::from_array(&self.params)
            }
        }
        impl ::core::convert::From<Params> for Model {
            fn from(params: Params) -> Self {
                Model::from_params(params)
            }
        }
    }
}

fn shape(shape: &Shape, docs: &ItemDocs) -> TokenStream {
    let ty = Ident::new(shape.ty, Span::call_site());
    let index = Ident::new(shape.index, Span::call_site());
    let len = Ident::new(shape.len, Span::call_site());
    let doc = shape.doc;
    let what = shape.what;
    let idents: Vec<Ident> = shape.names.iter().map(|n| format_ident!("{}", n)).collect();
    let fields = shape.names.iter().zip(&idents).map(|(name, ident)| {
        let line = format!(" {what} `{name}`.");
        let attrs = match docs.get(*name) {
            Some(attrs) if !attrs.is_empty() => quote! { #(#attrs)* },
            _ => quote! { #[doc = #line] },
        };
        quote! { #attrs pub #ident: f64 }
    });
    let to_array_doc = format!(
        " The array form, indexed by the constants of [`{}`].",
        shape.index
    );
    quote! {
        #[doc = #doc]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #ty {
            #(#fields,)*
        }
        impl #ty {
            #[doc = #to_array_doc]
            pub const fn to_array(&self) -> [f64; #len] {
                [#(self.#idents),*]
            }

            /// The named form of an array indexed by the constants of the index module.
            pub const fn from_array(values: &[f64; #len]) -> Self {
                #ty { #(#idents: values[#index::#idents]),* }
            }
        }
        impl ::core::convert::From<[f64; #len]> for #ty {
            fn from(values: [f64; #len]) -> Self {
                #ty::from_array(&values)
            }
        }
        impl ::core::convert::From<#ty> for [f64; #len] {
            fn from(named: #ty) -> Self {
                named.to_array()
            }
        }
    }
}
