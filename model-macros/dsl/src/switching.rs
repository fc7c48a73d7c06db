//! Switching, as written: `mode NAME { .. }` blocks and `when` events.
//!
//! A switched model is one set of states and parameters with several sets of equations (its
//! modes) and events that move the run between them. An event is a guard relation that starts
//! to hold, `when impact: h < 0`, located exactly by the runtime; what follows it is written as
//! a mechanics text says it: the states it resets (`{ v = -e * v; }`, every right-hand side read
//! just before the event) and the mode the run continues in (`-> sliding`), or `-> stop`. An
//! event with neither is only recorded. `when impact accumulates -> resting { .. }` says what an
//! accumulation of an event's resets (a Zeno point, such as a ball's ever shorter bounces)
//! turns into. A new state that no expression gives (the direction a slip starts in is the
//! solution of a search) is computed `by` a named Rust function: `-> sliding by slip_onset`.
//! The grammar is described in the macro crate's `DSL.md`, section "Switching".

use crate::ast::{Accumulates, Mode, Target, When};
use crate::expr::parse_relation;
use crate::skip::skip_all;
use crate::span::{Errors, SpanRange, Spans};
use crate::statements::{
    braced, check_docs_only, parse_binding, parse_equation, parse_name, recover_statement,
};
use model_algebra::Named;
use syn::parse::ParseStream;
use syn::Token;

/// Where parsed events go: a mode's lists or the model's shared ones.
pub(crate) struct Events<'a> {
    /// The events.
    pub events: &'a mut Vec<When>,
    /// The accumulation rules.
    pub accumulations: &'a mut Vec<Accumulates>,
}

/// `mode NAME { let ..; equations { .. } when .. }` (after the keyword `mode`).
pub(crate) fn parse_mode(
    input: ParseStream,
    attrs: Vec<syn::Attribute>,
    spans: &mut Spans,
    errors: &mut Errors,
) -> syn::Result<Mode> {
    let name: syn::Ident = input.parse()?;
    let id = spans.push(SpanRange::single(name.span()));
    let content = braced(input)?;
    let mut mode = Mode {
        attrs,
        name,
        id,
        lets: Vec::new(),
        equations: Vec::new(),
        events: Vec::new(),
        accumulations: Vec::new(),
        time_scale: None,
    };
    let mut equations_seen = false;
    while !content.is_empty() {
        let item_attrs = content.call(syn::Attribute::parse_outer)?;
        check_docs_only(&item_attrs, errors);
        if content.peek(Token![let]) {
            recover_statement(&content, errors, |input| {
                input.parse::<Token![let]>()?;
                mode.lets.push(parse_binding(input, spans)?);
                input.parse::<Token![;]>()?;
                Ok(())
            });
            continue;
        }
        let keyword: syn::Ident = match content.parse() {
            Ok(keyword) => keyword,
            Err(_) => {
                errors.push(content.error(format!(
                    "expected `let`, `equations {{ .. }}`, `when` or `time_scale` in mode `{}`",
                    mode.name
                )));
                skip_all(&content);
                break;
            }
        };
        match keyword.to_string().as_str() {
            "equations" => {
                if equations_seen {
                    errors.push(syn::Error::new(
                        keyword.span(),
                        format!(
                            "`equations` is written twice in mode `{}`: declare them in one section",
                            mode.name
                        ),
                    ));
                }
                equations_seen = true;
                let inner = braced(&content)?;
                while !inner.is_empty() {
                    recover_statement(&inner, errors, |input| {
                        mode.equations.push(parse_equation(input, spans)?);
                        Ok(())
                    });
                }
            }
            "when" => {
                let mut events = Events {
                    events: &mut mode.events,
                    accumulations: &mut mode.accumulations,
                };
                recover_statement(&content, errors, |input| {
                    parse_when(input, item_attrs, spans, &mut events)
                });
            }
            "time_scale" => {
                recover_statement(&content, errors, |input| {
                    parse_time_scale(input, &keyword, spans, &mut mode.time_scale)
                });
            }
            other => {
                errors.push(syn::Error::new(
                    keyword.span(),
                    format!(
                        "unknown section `{other}` in mode `{}`: expected `let`, `equations`, `when` or `time_scale` \
                         (parameters, states, outputs and options belong to the model)",
                        mode.name
                    ),
                ));
                skip_all(&content);
            }
        }
    }
    Ok(mode)
}

/// After the keyword `time_scale` (of a mode, or of the model): `= EXPR;`, the clock of
/// regularised time (`dt = EXPR dτ`), into `slot` (an error if it is already set).
pub(crate) fn parse_time_scale(
    input: ParseStream,
    keyword: &syn::Ident,
    spans: &mut Spans,
    slot: &mut Option<Named<crate::ast::Expr>>,
) -> syn::Result<()> {
    if slot.is_some() {
        return Err(syn::Error::new(
            keyword.span(),
            "`time_scale` is written twice here: a mode has one clock (the model's `time_scale` \
             is for the modes that declare none)",
        ));
    }
    if !input.peek(Token![=]) {
        return Err(input.error(
            "expected `=` and an expression after `time_scale`, e.g. `time_scale = theta / (theta + 0.01);`",
        ));
    }
    input.parse::<Token![=]>()?;
    let value = crate::expr::parse_expr(input, spans)?;
    input.parse::<Token![;]>()?;
    *slot = Some(Named {
        name: "time_scale".to_string(),
        id: spans.push(SpanRange::single(keyword.span())),
        value,
    });
    Ok(())
}

/// After the keyword `when`: `NAME: GUARD [-> TARGET] [{ RESETS } | by FUNCTION] [;]` or
/// `NAME accumulates -> TARGET [{ RESETS } | by FUNCTION] [;]`.
pub(crate) fn parse_when(
    input: ParseStream,
    attrs: Vec<syn::Attribute>,
    spans: &mut Spans,
    events: &mut Events,
) -> syn::Result<()> {
    let name = parse_name(input, spans)?;
    if input.peek(syn::Ident) {
        let word: syn::Ident = input.parse()?;
        if word != "accumulates" {
            return Err(syn::Error::new(
                word.span(),
                format!(
                    "expected `:` and a guard (`when {0}: h < 0`) or `accumulates` \
                     (`when {0} accumulates -> MODE`)",
                    name.name
                ),
            ));
        }
        if !input.peek(Token![->]) {
            return Err(input.error("expected `-> MODE` or `-> stop` after `accumulates`"));
        }
        let target = parse_target(input, spans)?
            .ok_or_else(|| input.error("expected `-> MODE` or `-> stop`"))?;
        let (resets, by) = parse_state_map(input, spans)?;
        end_of_event(input)?;
        events.accumulations.push(Accumulates {
            event: name,
            target,
            resets: resets.unwrap_or_default(),
            by,
        });
        return Ok(());
    }
    if !input.peek(Token![:]) {
        return Err(input.error(format!(
            "expected `:` and a guard after the event's name, e.g. `when {}: h < 0`",
            name.name
        )));
    }
    input.parse::<Token![:]>()?;
    let guard = parse_relation(input, spans)?;
    let target = parse_target(input, spans)?;
    let (resets, by) = parse_state_map(input, spans)?;
    end_of_event(input)?;
    events.events.push(When {
        attrs,
        name,
        guard,
        target,
        resets,
        by,
    });
    Ok(())
}

/// `-> NAME`, `-> stop` or a choice `-> a | b | stop`, if written.
fn parse_target(input: ParseStream, spans: &mut Spans) -> syn::Result<Option<Target>> {
    if !input.peek(Token![->]) {
        return Ok(None);
    }
    input.parse::<Token![->]>()?;
    let name = parse_name(input, spans)
        .map_err(|_| input.error("expected a mode's name or `stop` after `->`"))?;
    if input.peek(Token![|]) {
        let id = name.id;
        let mut names = vec![name];
        while input.peek(Token![|]) {
            input.parse::<Token![|]>()?;
            names.push(
                parse_name(input, spans)
                    .map_err(|_| input.error("expected a mode's name or `stop` after `|`"))?,
            );
        }
        let stop = names.iter().any(|n| n.name == "stop");
        names.retain(|n| n.name != "stop");
        return Ok(Some(Target::Choice {
            modes: names,
            stop,
            id,
        }));
    }
    Ok(Some(if name.name == "stop" {
        Target::Stop(name.id)
    } else {
        Target::Mode(name)
    }))
}

/// An event's new state as written: its resets `{ .. }` (`None` without braces), or the Rust
/// function that computes it.
type StateMap = (Option<Vec<Named<crate::ast::Expr>>>, Option<Named<()>>);

/// The new state, if the event sets one: written resets `{ .. }`, or `by FUNCTION`, a Rust
/// function that computes it (not both).
fn parse_state_map(input: ParseStream, spans: &mut Spans) -> syn::Result<StateMap> {
    let by = parse_by(input, spans)?;
    if by.is_some() && input.peek(syn::token::Brace) {
        return Err(input.error(
            "an event computes its new state `by` a Rust function or writes its resets \
             `{ .. }`, not both: assign these states in the function",
        ));
    }
    let resets = parse_resets(input, spans)?;
    if resets.is_some() && input.peek(syn::Ident) && input.fork().parse::<syn::Ident>()? == "by" {
        return Err(input.error(
            "an event writes its resets `{ .. }` or computes its new state `by` a Rust \
             function, not both: assign these states in the function",
        ));
    }
    Ok((resets, by))
}

/// `by FUNCTION`, if written: the name of the Rust function that computes the new state.
fn parse_by(input: ParseStream, spans: &mut Spans) -> syn::Result<Option<Named<()>>> {
    if !(input.peek(syn::Ident) && input.fork().parse::<syn::Ident>()? == "by") {
        return Ok(None);
    }
    input.parse::<syn::Ident>()?;
    let function = parse_name(input, spans).map_err(|_| {
        input.error("expected the name of a Rust function after `by`, e.g. `by slip_onset`")
    })?;
    Ok(Some(function))
}

/// `{ state = EXPR; .. }`, if written.
fn parse_resets(
    input: ParseStream,
    spans: &mut Spans,
) -> syn::Result<Option<Vec<Named<crate::ast::Expr>>>> {
    if !input.peek(syn::token::Brace) {
        return Ok(None);
    }
    let content = braced(input)?;
    let mut resets = Vec::new();
    while !content.is_empty() {
        resets.push(parse_binding(&content, spans)?);
        if content.is_empty() {
            break;
        }
        content.parse::<Token![;]>()?;
    }
    Ok(Some(resets))
}

/// An event ends with its braces or a `;` (both after braces are accepted).
fn end_of_event(input: ParseStream) -> syn::Result<()> {
    if input.peek(Token![;]) {
        input.parse::<Token![;]>()?;
        return Ok(());
    }
    if input.is_empty() || input.peek(syn::Ident) || input.peek(Token![#]) {
        return Ok(());
    }
    Err(input.error("expected `;`, `{ .. }` or `-> MODE` to end the event"))
}
