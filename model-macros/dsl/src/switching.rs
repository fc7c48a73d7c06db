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

use crate::ast::{Accumulates, Mode, ModeStates, ModelAst, Target, When};
use crate::expr::parse_relation;
use crate::include::include_here;
use crate::skip::skip_all;
use crate::span::{Errors, SpanRange, Spans};
use crate::statements::{
    braced, check_docs_only, no_docs_here, parse_binding, parse_equation, parse_list, parse_name,
    recover_statement,
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
    // `mode stopping like starting { .. }`: another mode's equations, with events of its own.
    let like = if input.peek(syn::Ident) {
        let word: syn::Ident = input.parse()?;
        if word != "like" {
            return Err(syn::Error::new(
                word.span(),
                format!("expected `{{` or `like MODE` after `mode {name}`"),
            ));
        }
        Some(parse_name(input, spans)?)
    } else {
        None
    };
    let content = braced(input)?;
    let mut mode = Mode {
        attrs,
        name,
        id,
        like,
        lets: Vec::new(),
        equations: Vec::new(),
        events: Vec::new(),
        accumulations: Vec::new(),
        time_scale: None,
        first_step: None,
        states: None,
    };
    let mut equations_seen = false;
    while !content.is_empty() {
        parse_mode_item(&content, &mut mode, &mut equations_seen, spans, errors)?;
    }
    Ok(mode)
}

/// One item of a mode's body (an `include`d file's items are items of the mode).
fn parse_mode_item(
    input: ParseStream,
    mode: &mut Mode,
    equations_seen: &mut bool,
    spans: &mut Spans,
    errors: &mut Errors,
) -> syn::Result<()> {
    let item_attrs = input.call(syn::Attribute::parse_outer)?;
    check_docs_only(&item_attrs, errors);
    if input.peek(Token![let]) {
        recover_statement(input, errors, |input| {
            input.parse::<Token![let]>()?;
            mode.lets.push(parse_binding(input, spans)?);
            input.parse::<Token![;]>()?;
            Ok(())
        });
        return Ok(());
    }
    let keyword: syn::Ident = match input.parse() {
        Ok(keyword) => keyword,
        Err(_) => {
            errors.push(input.error(format!(
                "expected `let`, `states {{ .. }} replace {{ .. }}`, `equations {{ .. }}`, `when`, `time_scale`, `first_step` or `include` in mode `{}`",
                mode.name
            )));
            skip_all(input);
            return Ok(());
        }
    };
    match keyword.to_string().as_str() {
        "equations" => {
            if *equations_seen {
                errors.push(syn::Error::new(
                    keyword.span(),
                    format!(
                        "`equations` is written twice in mode `{}`: declare them in one section",
                        mode.name
                    ),
                ));
            }
            *equations_seen = true;
            let inner = braced(input)?;
            while !inner.is_empty() {
                recover_statement(&inner, errors, |input| {
                    mode.equations.push(parse_equation(input, spans)?);
                    Ok(())
                });
            }
        }
        "include" => {
            no_docs_here(&item_attrs, "an `include`", errors);
            include_here(
                input,
                spans,
                |spans| spans,
                errors,
                |input, spans, errors| parse_mode_item(input, mode, equations_seen, spans, errors),
            );
        }
        "when" => {
            let mut events = Events {
                events: &mut mode.events,
                accumulations: &mut mode.accumulations,
            };
            recover_statement(input, errors, |input| {
                parse_when(input, item_attrs, spans, &mut events)
            });
        }
        word if Declared::of(word).is_some() => {
            let what = Declared::of(word).expect("matched");
            recover_statement(input, errors, |input| {
                parse_declared(input, &keyword, spans, what.slot(mode), what)
            });
        }
        "states" => {
            if mode.states.is_some() {
                errors.push(syn::Error::new(
                    keyword.span(),
                    format!("`states` is written twice in mode `{}`", mode.name),
                ));
            }
            let id = spans.push(SpanRange::single(keyword.span()));
            mode.states = Some(parse_mode_states(input, id, spans)?);
        }
        other => {
            errors.push(syn::Error::new(
                keyword.span(),
                format!(
                    "unknown section `{other}` in mode `{}`: expected `let`, `states`, `equations`, `when`, `time_scale`, \
                     `first_step` or `include` (parameters, outputs, discrete values and options belong to the model)",
                    mode.name
                ),
            ));
            skip_all(input);
        }
    }
    Ok(())
}

/// A number a mode declares besides its equations, `KEYWORD = EXPR;`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Declared {
    /// `time_scale`: the clock of regularised time (`dt = EXPR dτ`).
    TimeScale,
    /// `first_step`: the step the integrator tries first when the mode starts.
    FirstStep,
}

impl Declared {
    /// The declaration's keyword, if `word` is one.
    pub(crate) fn of(word: &str) -> Option<Declared> {
        match word {
            "time_scale" => Some(Declared::TimeScale),
            "first_step" => Some(Declared::FirstStep),
            _ => None,
        }
    }

    /// Where a mode keeps it.
    pub(crate) fn slot(self, mode: &mut Mode) -> &mut Option<Named<crate::ast::Expr>> {
        match self {
            Declared::TimeScale => &mut mode.time_scale,
            Declared::FirstStep => &mut mode.first_step,
        }
    }

    /// Where the model keeps it (for the modes that declare none).
    pub(crate) fn model_slot(self, model: &mut ModelAst) -> &mut Option<Named<crate::ast::Expr>> {
        match self {
            Declared::TimeScale => &mut model.time_scale,
            Declared::FirstStep => &mut model.first_step,
        }
    }

    fn example(self) -> &'static str {
        match self {
            Declared::TimeScale => "`time_scale = theta / (theta + 0.01);`",
            Declared::FirstStep => "`first_step = 1e-3 * abs(v / der(v));`",
        }
    }
}

/// After a declaration's keyword (of a mode, or of the model): `= EXPR;`, into `slot` (an
/// error if it is already set: a mode has one of each; the model's is for the modes that
/// declare none).
pub(crate) fn parse_declared(
    input: ParseStream,
    keyword: &syn::Ident,
    spans: &mut Spans,
    slot: &mut Option<Named<crate::ast::Expr>>,
    what: Declared,
) -> syn::Result<()> {
    if slot.is_some() {
        return Err(syn::Error::new(
            keyword.span(),
            format!(
                "`{keyword}` is written twice here: a mode has one (the model's `{keyword}` is \
                 for the modes that declare none)"
            ),
        ));
    }
    if !input.peek(Token![=]) {
        return Err(input.error(format!(
            "expected `=` and an expression after `{keyword}`, e.g. {}",
            what.example()
        )));
    }
    input.parse::<Token![=]>()?;
    let value = crate::expr::parse_expr(input, spans)?;
    input.parse::<Token![;]>()?;
    *slot = Some(Named {
        name: keyword.to_string(),
        id: spans.push(SpanRange::single(keyword.span())),
        value,
    });
    Ok(())
}

/// After `states` in a mode: `{ NEW, .. } replace { OLD, .. }`.
fn parse_mode_states(
    input: ParseStream,
    id: model_algebra::NodeId,
    spans: &mut Spans,
) -> syn::Result<ModeStates> {
    let mut states = ModeStates {
        id,
        new: Vec::new(),
        replace: Vec::new(),
    };
    let new = braced(input)?;
    parse_list(&new, &mut states.new, |input| parse_name(input, spans))?;
    let replace: syn::Ident = input.parse().map_err(|_| {
        input.error(
            "expected `replace { .. }`: a mode's states take the slots of states of the model",
        )
    })?;
    if replace != "replace" {
        return Err(syn::Error::new(
            replace.span(),
            "expected `replace { .. }`: a mode's states take the slots of states of the model",
        ));
    }
    let replaced = braced(input)?;
    parse_list(&replaced, &mut states.replace, |input| {
        parse_name(input, spans)
    })?;
    Ok(states)
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
