//! The model after the algebra: lower, split, structure, solve (all diagnostics collected);
//! then emit the states and outputs selected.
//!
//! [`Solved`] is the model after the algebra and before any choice of what to emit; the full
//! model and each reduced variant are emitted from one (a variant from its own, since its fixed
//! parameters change the algebra).

use std::collections::BTreeSet;

use crate::cse::{Emitter, Unbound};
use crate::expr::{ExprId, Pool, Sym};
use crate::jacobian::jacobian;
use crate::linear::{split, LinearForm};
use crate::lower::Lowerer;
use crate::options::CompileOptions;
use crate::print::to_dsl;
use crate::program::{CompiledModel, Explanation, Operand, Program, Target};
use crate::solve::{solve_block, BlockSystem, Sampler, SolveContext};
use crate::spec::{Diagnostic, ModelSpec, NodeId};
use crate::structure::blocks;
use crate::structure_messages::{derivatives, labels};
use crate::system::{Pivot, System};
use crate::trig::{self, Rewritten};

/// Which states and outputs to emit (original indices, ascending).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Selection {
    /// Kept states.
    pub states: Vec<usize>,
    /// Kept outputs.
    pub outputs: Vec<usize>,
}

/// A model after the algebra: the solved right-hand side and the outputs.
pub struct Solved {
    /// The expressions.
    pub pool: Pool,
    /// `der(y_i)` for every state, as definitions.
    pub system: System,
    /// Each output's expression (reading derivatives as inputs).
    pub outputs: Vec<ExprId>,
    /// The parameters fixed at compile time.
    pub fixed: Vec<Option<f64>>,
    /// [`CompileOptions::pivot_tolerance`].
    pub pivot_tolerance: f64,
}

impl Solved {
    /// Lowers and solves `spec` with parameter `i` fixed to `fixed[i]` where given.
    pub fn build(
        spec: &ModelSpec,
        fixed: Vec<Option<f64>>,
        options: &CompileOptions,
    ) -> Result<Solved, Vec<Diagnostic>> {
        let n = spec.states.len();
        let mut lower = Lowerer::new(spec, fixed.clone());
        let mut diags = Vec::new();
        if n == 0 {
            diags.push(Diagnostic {
                id: spec.equations.first().map_or(NodeId(0), |e| e.id),
                message: "the model has no states".into(),
            });
        }
        let mut forms: Vec<Option<LinearForm>> = Vec::new();
        for (k, eq) in spec.equations.iter().enumerate() {
            let form = lower
                .equation(k)
                .and_then(|r| match split(&mut lower.pool, r) {
                    Ok(f) => Some(f),
                    Err(_) => {
                        lower.diags.push(Diagnostic {
                            id: eq.id,
                            message: format!("`{}` is not linear in the derivatives", eq.label),
                        });
                        None
                    }
                });
            forms.push(form);
        }
        let outputs: Vec<Option<ExprId>> =
            (0..spec.outputs.len()).map(|k| lower.output(k)).collect();
        diags.append(&mut lower.diags);
        let mut pool = lower.pool;
        if !diags.is_empty() || forms.iter().any(|f| f.is_none()) {
            return Err(diags);
        }
        let forms: Vec<LinearForm> = forms.into_iter().flatten().collect();
        let algebraic = crate::structure_messages::algebraic_equations(spec, &forms);
        if !algebraic.is_empty() {
            return Err(algebraic);
        }
        let outputs: Vec<ExprId> = outputs.into_iter().flatten().collect();
        let system = solve_all(&mut pool, spec, &forms, options)?;
        Ok(Solved {
            pool,
            system,
            outputs,
            fixed,
            pivot_tolerance: options.pivot_tolerance,
        })
    }

    /// The input symbols the stored derivatives of `states` read, through the definitions.
    pub fn inputs_of_ders(&mut self, states: &[usize]) -> BTreeSet<Sym> {
        let roots: Vec<ExprId> = states.iter().map(|&i| self.pool.sym(Sym::Der(i))).collect();
        self.system.inputs_read(&self.pool, &roots)
    }

    /// Emits the programs for `selection` as a model named `name`.
    pub fn emit(
        &mut self,
        spec: &ModelSpec,
        name: &str,
        selection: &Selection,
    ) -> Result<CompiledModel, Unbound> {
        let n = spec.states.len();
        let mut state_map = vec![None; n];
        for (new, &old) in selection.states.iter().enumerate() {
            state_map[old] = Some(new);
        }
        let mut param_map = vec![None; spec.params.len()];
        let mut params = Vec::new();
        for (i, p) in spec.params.iter().enumerate() {
            if self.fixed[i].is_none() {
                param_map[i] = Some(params.len());
                params.push((p.name.clone(), p.value));
            }
        }
        let rhs_input = |s: Sym| -> Option<Operand> {
            match s {
                Sym::State(i) => state_map.get(i).copied().flatten().map(Operand::State),
                Sym::Param(i) => param_map.get(i).copied().flatten().map(Operand::Param),
                Sym::Time => Some(Operand::Time),
                _ => None,
            }
        };
        let output_input = |s: Sym| -> Option<Operand> {
            match s {
                Sym::Der(i) => state_map.get(i).copied().flatten().map(Operand::Der),
                other => rhs_input(other),
            }
        };
        let ders: Vec<ExprId> = selection
            .states
            .iter()
            .map(|&i| self.pool.sym(Sym::Der(i)))
            .collect();

        let mut roots = ders.clone();
        roots.extend(selection.outputs.iter().map(|&k| self.outputs[k]));
        let Rewritten { system, outputs } = trig::rewrite(
            &mut self.pool,
            &self.system,
            &self.outputs,
            &roots,
            &|pool, e| to_dsl(pool, e, &|s| symbol_name(spec, s)),
        );
        let tolerance = self.pivot_tolerance;

        let mut e = Emitter::new(&mut self.pool, &system, &rhs_input, &ders, tolerance);
        for (new, &d) in ders.iter().enumerate() {
            e.store(Target::Der(new), d)?;
        }
        let (pivots, numeric_blocks) = (e.pivots.clone(), e.numeric_blocks.clone());
        let rhs = e.finish();

        let mut jac_system = system.clone();
        let entries = jacobian(
            &mut self.pool,
            &mut jac_system,
            &selection.states,
            &selection.states,
        );
        let mut roots: Vec<ExprId> = entries.iter().map(|x| x.value).collect();
        for &i in &selection.states {
            if let Some(g) = system.owner(Sym::Der(i)) {
                roots.extend(system.groups[g].pivots.iter().map(|p| p.value));
            }
        }
        let mut e = Emitter::new(&mut self.pool, &jac_system, &rhs_input, &roots, tolerance);
        for &i in &selection.states {
            e.check_pivots_of(Sym::Der(i))?;
        }
        for x in &entries {
            let (Some(r), Some(c)) = (state_map[x.row], state_map[x.col]) else {
                continue;
            };
            e.store(Target::Jac(r, c), x.value)?;
        }
        let jacobian_program = e.finish();

        let empty = System::default();
        let outs: Vec<ExprId> = selection.outputs.iter().map(|&k| outputs[k]).collect();
        let mut e = Emitter::new(&mut self.pool, &empty, &output_input, &outs, tolerance);
        for (new, &o) in outs.iter().enumerate() {
            e.store(Target::Output(new), o)?;
        }
        let outputs_program: Program = e.finish();

        Ok(CompiledModel {
            name: name.to_string(),
            states: selection
                .states
                .iter()
                .map(|&i| spec.states[i].name.clone())
                .collect(),
            params,
            outputs: selection
                .outputs
                .iter()
                .map(|&k| spec.outputs[k].name.clone())
                .collect(),
            rhs,
            jacobian: jacobian_program,
            outputs_program,
            pivots,
            numeric_blocks,
            variants: Vec::new(),
            explanation: Explanation::default(),
            initial: vec![None; selection.states.len()],
        })
    }
}

/// The user's name of a symbol, for pivot texts.
pub fn symbol_name(spec: &ModelSpec, s: Sym) -> String {
    let state = |i: usize| {
        spec.states
            .get(i)
            .map_or_else(|| format!("y{i}"), |s| s.name.clone())
    };
    match s {
        Sym::Time => "t".into(),
        Sym::State(i) => state(i),
        Sym::Param(i) => spec
            .params
            .get(i)
            .map_or_else(|| format!("p{i}"), |p| p.name.clone()),
        Sym::Der(i) => format!("der({})", state(i)),
        Sym::Aux(k) => format!("aux{k}"),
    }
}

/// A solved derivative costing at most this many operations is substituted into later blocks
/// instead of read as a symbol, so that it can cancel against its coefficient (`sin(theta)`
/// times `der(psi) = -Omega_x/sin(theta)` is `-Omega_x`). Substitution costs nothing at run
/// time: the expression is shared, so it is still computed once.
pub const INLINE_OPS: u32 = 4;

/// `der(y_j)` as later blocks see it: its solution if that is small (then the pivots guarding
/// it are added to `inherited`), else its symbol.
fn known_derivative(
    pool: &mut Pool,
    system: &System,
    j: usize,
    inherited: &mut Vec<Pivot>,
) -> ExprId {
    match system.expression_of(Sym::Der(j)) {
        Some(e) if pool.dag_ops(&[e]) <= INLINE_OPS => {
            if let Some(g) = system.owner(Sym::Der(j)) {
                for p in &system.groups[g].pivots {
                    if !inherited.contains(p) {
                        inherited.push(p.clone());
                    }
                }
            }
            e
        }
        _ => pool.sym(Sym::Der(j)),
    }
}

/// Structure and solve of all blocks, in order.
fn solve_all(
    pool: &mut Pool,
    spec: &ModelSpec,
    forms: &[LinearForm],
    options: &CompileOptions,
) -> Result<System, Vec<Diagnostic>> {
    let n = spec.states.len();
    let incidence: Vec<Vec<usize>> = forms
        .iter()
        .map(|f| f.coefficients.keys().copied().collect())
        .collect();
    let order = blocks(&incidence, n)
        .map_err(|error| crate::structure_messages::structure_error(spec, &error))?;
    let text = |pool: &Pool, e: ExprId| to_dsl(pool, e, &|s| symbol_name(spec, s));
    let param = |i: usize| spec.params.get(i).and_then(|p| p.value).unwrap_or(1.0);
    let sampler = Sampler {
        param: &param,
        n_states: n,
    };
    let ctx = SolveContext {
        text: &text,
        sampler: &sampler,
        swell_bound: options.swell_bound,
    };
    let mut system = System::default();
    let mut diags = Vec::new();
    for block in order {
        let m = block.vars.len();
        let mut inherited = Vec::new();
        let mut matrix = Vec::with_capacity(m * m);
        let mut rhs = Vec::with_capacity(m);
        for &eq in &block.equations {
            let f = &forms[eq];
            for &v in &block.vars {
                matrix.push(f.coefficients.get(&v).copied().unwrap_or(ExprId::ZERO));
            }
            let mut terms = vec![f.rest];
            for (&j, &c) in &f.coefficients {
                if !block.vars.contains(&j) {
                    let d = known_derivative(pool, &system, j, &mut inherited);
                    terms.push(pool.mul2(c, d));
                }
            }
            let s = pool.add(&terms);
            rhs.push(pool.neg(s));
        }
        let bs = BlockSystem {
            matrix,
            rhs,
            vars: block.vars.clone(),
        };
        match solve_block(pool, &bs, &ctx) {
            Ok(mut sol) => {
                for p in sol.group.pivots.drain(..) {
                    if !inherited.contains(&p) {
                        inherited.push(p);
                    }
                }
                sol.group.pivots = inherited;
                system.push(sol.group);
            }
            Err(singular) => diags.push(Diagnostic {
                id: spec.equations[block.equations[0]].id,
                message: format!(
                    "equations {} are singular: their coefficients of {} cancel identically",
                    labels(spec, &block.equations),
                    derivatives(spec, &singular.vars)
                ),
            }),
        }
    }
    if diags.is_empty() {
        Ok(system)
    } else {
        Err(diags)
    }
}
