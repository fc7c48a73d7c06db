//! Name resolution and every check that needs only the model as written.
//!
//! The algebra crate trusts its input (names resolved, one equation per state, no cycles), so all
//! of that is decided here, in the user's terms, before any algebra runs. Every problem is
//! collected; the model is rejected once, with all of them.

use crate::ast::{Call, Expr, ModelAst};
use crate::names::{function_list, Decl, Kind, Names, DER};
use crate::options::compile_options;
use crate::span::{Errors, SpanRange};
use model_algebra::CompileOptions;
use model_algebra::{Ast, Condition, EquationSpec, Func, ModelSpec, Named, NodeId, VariantSpec};
use std::collections::{BTreeMap, BTreeSet};

/// Module names the emitter uses inside every model, so a variant cannot take them.
/// Names of the items every model module emits, which a variant's module cannot take.
pub const RESERVED_MODULES: [&str; 7] = [
    "state", "param", "output", "Model", "Params", "State", "Outputs",
];

/// A model ready for the compiler.
#[derive(Clone, Debug)]
pub struct Validated {
    /// The model as written (for a chart: the model in the chart's coordinates).
    pub ast: ModelAst,
    /// The model with its names resolved.
    pub spec: ModelSpec,
    /// The compiler's options for it.
    pub options: CompileOptions,
}

/// Checks the model and resolves its names; `Err` carries every problem found. `Ok` holds the
/// model, then the model in each of its charts (checked only once the model itself is valid,
/// so a mistake in a shared row is reported once).
pub fn validate(ast: &ModelAst) -> syn::Result<Vec<Validated>> {
    let model = validate_one(ast)?;
    let mut errors = Errors::default();
    let mut models = vec![model];
    for chart in &ast.charts {
        match validate_one(&chart.apply(ast)) {
            Ok(model) => models.push(model),
            Err(error) => errors.push(error),
        }
    }
    errors.finish()?;
    Ok(models)
}

pub(crate) fn validate_one(ast: &ModelAst) -> syn::Result<Validated> {
    let mut validator = Validator {
        ast,
        names: Names::new(),
        errors: Errors::default(),
        let_props: BTreeMap::new(),
        output_props: Vec::new(),
    };
    crate::limits::check_let_depth(ast)?;
    // A model needs states (whether the equations match them one to one is the compiler's
    // structure analysis); without any, every use of one would be an unknown name.
    if let Some(error) = crate::states::missing_states(ast) {
        return Err(error);
    }
    validator.check_item_docs();
    validator.declare_all();
    validator.check_let_cycles();
    validator.compute_let_props();
    let lets = validator.resolve_lets();
    let equations = validator.resolve_equations();
    let outputs = validator.resolve_outputs();
    validator.check_labels();
    let variants = validator.check_variants();
    let options = compile_options(&ast.options, &ast.spans, &mut validator.errors);
    crate::chart::check(ast, &validator.names, &mut validator.errors);
    validator.errors.finish()?;
    let spec = ModelSpec {
        name: ast.name.to_string(),
        params: ast.params.clone(),
        states: ast.states.clone(),
        lets,
        equations,
        outputs,
        variants,
    };
    Ok(Validated {
        ast: ast.clone(),
        spec,
        options,
    })
}

/// What an expression depends on, through lets and outputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Props {
    /// It reads a state or `t`: its time derivative need not be zero.
    varies: bool,
    /// It contains `der(..)`.
    has_der: bool,
}

impl Props {
    fn or(self, other: Props) -> Props {
        Props {
            varies: self.varies || other.varies,
            has_der: self.has_der || other.has_der,
        }
    }
}

/// Where an expression is written, which decides which names it may use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scope {
    Let,
    Equation,
    /// The output at this position.
    Output(usize),
}

struct Validator<'a> {
    ast: &'a ModelAst,
    names: Names,
    errors: Errors,
    let_props: BTreeMap<&'a str, Props>,
    output_props: Vec<Props>,
}

impl<'a> Validator<'a> {
    fn range(&self, id: NodeId) -> SpanRange {
        self.ast.spans.range(id)
    }

    fn check_item_docs(&mut self) {
        let attrs = self.ast.docs.values().flatten();
        for attr in attrs.filter(|attr| !attr.path().is_ident("doc")) {
            self.errors.push(syn::Error::new_spanned(
                attr,
                "only doc comments (`/// ..`) are allowed in a model",
            ));
        }
    }

    fn declare_all(&mut self) {
        let ast = self.ast;
        let params = ast.params.iter().map(|p| (&p.name, p.id, Kind::Param));
        let states = ast.states.iter().map(|s| (&s.name, s.id, Kind::State));
        let lets = ast.lets.iter().map(|l| (&l.name, l.id, Kind::Let));
        let outputs =
            (ast.outputs.iter().enumerate()).map(|(k, o)| (&o.name, o.id, Kind::Output(k)));
        for (name, id, kind) in params.chain(states).chain(lets).chain(outputs) {
            if let Err(earlier) = self.names.declare(name, kind, id) {
                let message = match earlier.id {
                    None => format!("`{name}` is reserved: it is {}", earlier.kind),
                    Some(_) => {
                        format!("`{name}` is declared twice: it is already {}", earlier.kind)
                    }
                };
                self.errors.at(self.range(id), message);
            }
        }
    }

    /// The let declared under `name`, if `name` is a let (the first declaration wins).
    fn let_named(&self, name: &str) -> Option<&'a Named<Expr>> {
        match self.names.get(name)?.kind {
            Kind::Let => self.ast.lets.iter().find(|l| l.name == name),
            _ => None,
        }
    }

    /// The lets an expression refers to directly, in order of first appearance.
    fn let_refs(&self, expr: &'a Expr) -> Vec<&'a str> {
        let mut refs: Vec<&'a str> = Vec::new();
        expr.walk(&mut |node| {
            if let Expr::Name(_, name) = node {
                if self.let_named(name).is_some() && !refs.contains(&name.as_str()) {
                    refs.push(name);
                }
            }
        });
        refs
    }

    fn check_let_cycles(&mut self) {
        #[derive(Clone, Copy, PartialEq)]
        enum Color {
            White,
            Gray,
            Black,
        }
        let lets = &self.ast.lets;
        let mut color: BTreeMap<&str, Color> = lets
            .iter()
            .map(|l| (l.name.as_str(), Color::White))
            .collect();
        let mut cycles: Vec<Vec<&str>> = Vec::new();
        // Iterative DFS: (let, index of the next reference to follow).
        for root in lets {
            if color[root.name.as_str()] != Color::White {
                continue;
            }
            let mut path: Vec<(&str, Vec<&str>, usize)> = Vec::new();
            color.insert(&root.name, Color::Gray);
            path.push((&root.name, self.let_refs(&root.value), 0));
            while let Some((node, refs, next)) = path.last_mut() {
                if *next == refs.len() {
                    color.insert(node, Color::Black);
                    path.pop();
                    continue;
                }
                let target = refs[*next];
                *next += 1;
                match color.get(target).copied().unwrap_or(Color::Black) {
                    Color::White => {
                        color.insert(target, Color::Gray);
                        let refs = self.let_named(target).map(|l| self.let_refs(&l.value));
                        path.push((target, refs.unwrap_or_default(), 0));
                    }
                    Color::Gray => {
                        let start = path.iter().position(|(n, ..)| *n == target).unwrap_or(0);
                        let mut cycle: Vec<&str> = path[start..].iter().map(|(n, ..)| *n).collect();
                        cycle.push(target);
                        cycles.push(cycle);
                    }
                    Color::Black => {}
                }
            }
        }
        for cycle in cycles {
            let shown: Vec<String> = cycle.iter().map(|n| format!("`{n}`")).collect();
            if let Some(first) = self.let_named(cycle[0]) {
                let message = format!("cycle among lets: {}", shown.join(" -> "));
                self.errors.at(self.range(first.id), message);
            }
        }
    }

    fn compute_let_props(&mut self) {
        let mut memo: BTreeMap<&'a str, Option<Props>> = BTreeMap::new();
        for binding in &self.ast.lets {
            self.let_props_memo(&binding.name, &mut memo);
        }
        self.let_props = memo
            .into_iter()
            .filter_map(|(name, props)| Some((name, props?)))
            .collect();
    }

    fn let_props_memo(&self, name: &'a str, memo: &mut BTreeMap<&'a str, Option<Props>>) -> Props {
        match memo.get(name) {
            Some(Some(props)) => return *props,
            // In progress: a cycle, already reported.
            Some(None) => return Props::default(),
            None => {}
        }
        let Some(binding) = self.let_named(name) else {
            return Props::default();
        };
        memo.insert(name, None);
        let props = self.expr_props(&binding.value, &mut |v, n| v.let_props_memo(n, memo));
        memo.insert(name, Some(props));
        props
    }

    fn expr_props(
        &self,
        expr: &'a Expr,
        let_props: &mut dyn FnMut(&Self, &'a str) -> Props,
    ) -> Props {
        match expr {
            Expr::Num(..) => Props::default(),
            Expr::Name(_, name) => match self.names.get(name).map(|d| d.kind) {
                Some(Kind::State | Kind::Time) => Props {
                    varies: true,
                    has_der: false,
                },
                Some(Kind::Let) => let_props(self, name),
                Some(Kind::Output(k)) => self.output_props.get(k).copied().unwrap_or_default(),
                _ => Props::default(),
            },
            Expr::Neg(_, arg) => self.expr_props(arg, let_props),
            Expr::Bin(_, _, lhs, rhs) => self
                .expr_props(lhs, let_props)
                .or(self.expr_props(rhs, let_props)),
            Expr::Call(call) => {
                let mut props = Props::default();
                for arg in &call.args {
                    props = props.or(self.expr_props(arg, let_props));
                }
                if call.func == DER {
                    props.has_der = true;
                }
                props
            }
            Expr::If {
                cond,
                then,
                otherwise,
                ..
            } => [&cond.lhs, &cond.rhs, then, otherwise]
                .into_iter()
                .fold(Props::default(), |props, e| {
                    props.or(self.expr_props(e, let_props))
                }),
        }
    }

    /// Properties of an expression once every let's properties are known.
    fn props(&self, expr: &'a Expr) -> Props {
        self.expr_props(expr, &mut |v, name| {
            v.let_props.get(name).copied().unwrap_or_default()
        })
    }

    fn resolve_lets(&mut self) -> Vec<Named<Ast>> {
        let ast = self.ast;
        ast.lets
            .iter()
            .filter_map(|binding| {
                let value = self.resolve(&binding.value, Scope::Let)?;
                Some(Named {
                    name: binding.name.clone(),
                    id: binding.id,
                    value,
                })
            })
            .collect()
    }

    fn resolve_equations(&mut self) -> Vec<EquationSpec> {
        let ast = self.ast;
        let mut equations = Vec::new();
        for (k, equation) in ast.equations.iter().enumerate() {
            let lhs = self.resolve(&equation.lhs, Scope::Equation);
            let rhs = self.resolve(&equation.rhs, Scope::Equation);
            let label = match &equation.label {
                Some(label) => label.name.clone(),
                None => format!("equation {}", k + 1),
            };
            let id = equation.id;
            if let (Some(lhs), Some(rhs)) = (lhs, rhs) {
                equations.push(EquationSpec {
                    label,
                    id,
                    lhs,
                    rhs,
                });
            }
        }
        equations
    }

    fn resolve_outputs(&mut self) -> Vec<Named<Ast>> {
        let ast = self.ast;
        let mut outputs = Vec::new();
        for (k, binding) in ast.outputs.iter().enumerate() {
            let value = self.resolve(&binding.value, Scope::Output(k));
            let props = self.props(&binding.value);
            self.output_props.push(props);
            if let Some(value) = value {
                outputs.push(Named {
                    name: binding.name.clone(),
                    id: binding.id,
                    value,
                });
            }
        }
        outputs
    }

    /// Resolves an expression; `None` when it has an error (every error is recorded).
    fn resolve(&mut self, expr: &'a Expr, scope: Scope) -> Option<Ast> {
        match expr {
            Expr::Num(id, value) => Some(Ast::Num(*id, *value)),
            // Declared twice: reported once at the declaration, not again at every use.
            Expr::Name(_, name) if self.names.is_clashed(name) => None,
            Expr::Name(id, name) => match self.name_error(name, scope) {
                Some(message) => {
                    self.errors.at(self.range(*id), message);
                    None
                }
                None => Some(Ast::Name(*id, name.clone())),
            },
            Expr::Neg(id, arg) => Some(Ast::Neg(*id, Box::new(self.resolve(arg, scope)?))),
            Expr::Bin(id, op, lhs, rhs) => {
                let lhs = self.resolve(lhs, scope);
                let rhs = self.resolve(rhs, scope);
                Some(Ast::Bin(*id, *op, Box::new(lhs?), Box::new(rhs?)))
            }
            Expr::Call(call) => self.resolve_call(call, scope),
            Expr::If {
                id,
                cond,
                then,
                otherwise,
            } => {
                let [lhs, rhs, then, otherwise] =
                    [&cond.lhs, &cond.rhs, then, otherwise].map(|e| self.resolve(e, scope));
                let Some(op) = cond.op.ordering() else {
                    let message = "`if` cannot test `==`: compare with `<`, `<=`, `>` or `>=`";
                    self.errors.at(self.range(cond.id), message);
                    return None;
                };
                let cond = Condition {
                    id: cond.id,
                    lhs: lhs?,
                    op,
                    rhs: rhs?,
                };
                Some(Ast::If(
                    *id,
                    Box::new(cond),
                    Box::new(then?),
                    Box::new(otherwise?),
                ))
            }
        }
    }

    /// Why `name` cannot be used in `scope`, or `None` if it can.
    fn name_error(&self, name: &str, scope: Scope) -> Option<String> {
        let outputs_before = match scope {
            Scope::Output(k) => k,
            Scope::Let | Scope::Equation => 0,
        };
        let Some(Decl { kind, .. }) = self.names.get(name) else {
            let hint = match self.names.suggest(name, outputs_before, false) {
                Some(close) => format!(" (did you mean `{close}`?)"),
                None => String::new(),
            };
            return Some(format!(
                "unknown name `{name}`{hint}; usable here: {}",
                self.names.describe_usable(outputs_before)
            ));
        };
        match (kind, scope) {
            (Kind::Function, _) => Some(format!("`{name}` is a function: call it as `{name}(..)`")),
            (Kind::Output(_), Scope::Let | Scope::Equation) => Some(format!(
                "`{name}` is an output: outputs are computed after the solve and can be used only in later outputs"
            )),
            (Kind::Output(k), Scope::Output(current)) if k == current => {
                Some(format!("output `{name}` refers to itself"))
            }
            (Kind::Output(k), Scope::Output(current)) if k > current => Some(format!(
                "output `{name}` is used before it is defined: outputs are computed in order, so move `{name}` above `{}`",
                self.ast.outputs[current].name
            )),
            _ => None,
        }
    }

    fn resolve_call(&mut self, call: &'a Call, scope: Scope) -> Option<Ast> {
        let args: Vec<Option<Ast>> = call.args.iter().map(|a| self.resolve(a, scope)).collect();
        let name = call.func.as_str();
        let (func, arity) = if name == DER {
            (None, 1)
        } else if let Some(func) = Func::from_name(name) {
            (Some(func), func.arity())
        } else {
            let message = match self.names.get(name) {
                Some(decl) => format!("`{name}` is {}, not a function", decl.kind),
                // A hybrid-systems habit: `pre(v)` for the value before the event.
                None if name == "pre" => {
                    let inner = match call.args.as_slice() {
                        [Expr::Name(_, inner)] => inner.as_str(),
                        _ => "x",
                    };
                    format!(
                        "there is no `pre`: a reset already reads every value as it was just \
                         before the event, so write `{inner}` for `pre({inner})`"
                    )
                }
                None => {
                    let hint = match self.names.suggest(name, 0, true) {
                        Some(close) => format!(" (did you mean `{close}`?)"),
                        None => String::new(),
                    };
                    format!(
                        "unknown function `{name}`{hint}; the functions are {}",
                        function_list()
                    )
                }
            };
            self.errors.at(self.range(call.func_id), message);
            return None;
        };
        if args.len() != arity {
            let plural = if arity == 1 { "" } else { "s" };
            let message = format!(
                "`{name}` takes {arity} argument{plural}, found {}",
                args.len()
            );
            self.errors.at(self.range(call.id), message);
            return None;
        }
        let args: Vec<Ast> = args.into_iter().collect::<Option<_>>()?;
        match func {
            Some(func) => Some(Ast::Call(call.id, func, args)),
            None => {
                let arg = args.into_iter().next()?;
                self.check_der_argument(call)?;
                Some(Ast::Der(call.id, Box::new(arg)))
            }
        }
    }

    /// `der(arg)` must vary in time and be first order.
    fn check_der_argument(&mut self, call: &'a Call) -> Option<()> {
        let arg = call.args.first()?;
        let range = self.range(call.id);
        if let Expr::Name(_, name) = arg {
            if self.names.get(name).map(|d| d.kind) == Some(Kind::Param) {
                self.errors.at(
                    range,
                    format!("`der({name})`: `{name}` is a parameter, which is constant; `der` applies to expressions of the states"),
                );
                return None;
            }
        }
        let props = self.props(arg);
        if !props.varies {
            self.errors.at(
                range,
                "`der` of an expression with no state and no `t`: its derivative is zero",
            );
            return None;
        }
        if props.has_der {
            self.errors.at(
                range,
                "nested `der`: the equations must be first order; introduce a state for the rate instead",
            );
            return None;
        }
        Some(())
    }

    fn check_labels(&mut self) {
        let mut seen = BTreeSet::new();
        for label in self.ast.equations.iter().filter_map(|e| e.label.as_ref()) {
            if !seen.insert(label.name.as_str()) {
                let message = format!("equation label `{}` is used twice", label.name);
                self.errors.at(self.range(label.id), message);
            }
        }
    }

    fn check_variants(&mut self) -> Vec<VariantSpec> {
        let ast = self.ast;
        let mut seen = BTreeSet::new();
        let mut variants = Vec::new();
        for variant in &ast.variants {
            let name = variant.name.to_string();
            let range = self.range(variant.id);
            if RESERVED_MODULES.contains(&name.as_str()) {
                self.errors.at(
                    range,
                    format!(
                        "a variant cannot be called `{name}`: the model already defines `{name}`"
                    ),
                );
            } else if !seen.insert(name.clone()) {
                self.errors
                    .at(range, format!("variant `{name}` is declared twice"));
            }
            if variant.keep.is_empty() {
                self.errors
                    .at(range, format!("variant `{name}` keeps nothing"));
            }
            let mut kept = BTreeSet::new();
            for keep in &variant.keep {
                let kind = self.names.get(&keep.name).map(|d| d.kind);
                let range = self.range(keep.id);
                if !matches!(kind, Some(Kind::State | Kind::Output(_))) {
                    let message = format!(
                        "variant `{name}` keeps `{}`, which is not a state or an output; {}",
                        keep.name,
                        self.names.describe_keepable()
                    );
                    self.errors.at(range, message);
                } else if !kept.insert(keep.name.as_str()) {
                    self.errors
                        .at(range, format!("`{}` is kept twice", keep.name));
                }
            }
            let mut fixed = BTreeSet::new();
            for fix in &variant.fix {
                let kind = self.names.get(&fix.name).map(|d| d.kind);
                let range = self.range(fix.id);
                if kind != Some(Kind::Param) {
                    let message = format!(
                        "variant `{name}` fixes `{}`, which is not a parameter; {}",
                        fix.name,
                        self.names.describe_params()
                    );
                    self.errors.at(range, message);
                } else if !fixed.insert(fix.name.as_str()) {
                    self.errors
                        .at(range, format!("`{}` is fixed twice", fix.name));
                }
            }
            variants.push(VariantSpec {
                name,
                id: variant.id,
                keep: variant.keep.clone(),
                fix: variant.fix.clone(),
            });
        }
        variants
    }
}
