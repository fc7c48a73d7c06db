//! Which equation determines which derivative, and in what order the blocks can be solved.
//!
//! A maximum matching of equations to the derivatives they contain proves the mass matrix is
//! structurally regular; the strongly connected components of the matched dependency graph
//! (Tarjan) give the block lower triangular form, so each block is solved alone, smallest
//! first, with the earlier blocks' solutions known. A 12-state mechanical model usually falls
//! apart into many 1×1 blocks and one or two small coupled ones. When no perfect matching
//! exists, the Hall set reached from an unmatched equation names exactly the equations that
//! cannot determine their derivatives.

/// Equations solved together for the same number of derivatives.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Block {
    /// Equation indices, ascending.
    pub equations: Vec<usize>,
    /// Derivative (state) indices, ascending.
    pub vars: Vec<usize>,
}

/// Why the derivatives cannot be solved for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StructureError {
    /// These derivatives appear in no equation.
    Unused(Vec<usize>),
    /// No assignment of one derivative to each equation exists.
    Singular {
        /// An equation left over (when there are more equations than derivatives to share):
        /// the one the message points at.
        surplus: Option<usize>,
        /// The equations involved, ascending: those that contain only `vars` (with a surplus),
        /// or those the undetermined derivatives share.
        equations: Vec<usize>,
        /// The derivatives `equations` contain, ascending.
        vars: Vec<usize>,
        /// Every derivative that some maximum matching leaves without an equation, ascending
        /// (empty when only equations are left over).
        undetermined: Vec<usize>,
    },
}

/// Blocks in solve order from the incidence `incidence[equation] = derivatives it contains`.
pub fn blocks(incidence: &[Vec<usize>], n_vars: usize) -> Result<Vec<Block>, StructureError> {
    let mut used = vec![false; n_vars];
    for vars in incidence {
        for &v in vars {
            used[v] = true;
        }
    }
    let unused: Vec<usize> = (0..n_vars).filter(|&v| !used[v]).collect();
    if !unused.is_empty() {
        return Err(StructureError::Unused(unused));
    }
    let matching = maximum_matching(incidence, n_vars);
    let (undetermined, shared) = undetermined(incidence, &matching);
    if let Some(e) = (0..incidence.len()).find(|&e| matching.var_of_eq[e].is_none()) {
        let (equations, vars) = hall_set(incidence, &matching, e);
        return Err(StructureError::Singular {
            surplus: Some(e),
            equations,
            vars,
            undetermined,
        });
    }
    if !undetermined.is_empty() {
        return Err(StructureError::Singular {
            surplus: None,
            equations: shared,
            vars: undetermined.clone(),
            undetermined,
        });
    }
    Ok(tarjan_blocks(incidence, &matching))
}

/// A matching between equations and derivatives.
#[derive(Clone, Debug)]
struct Matching {
    var_of_eq: Vec<Option<usize>>,
    eq_of_var: Vec<Option<usize>>,
}

fn maximum_matching(incidence: &[Vec<usize>], n_vars: usize) -> Matching {
    let mut m = Matching {
        var_of_eq: vec![None; incidence.len()],
        eq_of_var: vec![None; n_vars],
    };
    for e in 0..incidence.len() {
        let mut visited = vec![false; n_vars];
        augment(incidence, &mut m, e, &mut visited);
    }
    m
}

/// Kuhn's augmenting path search from equation `e`.
fn augment(incidence: &[Vec<usize>], m: &mut Matching, e: usize, visited: &mut [bool]) -> bool {
    for &v in &incidence[e] {
        if visited[v] {
            continue;
        }
        visited[v] = true;
        let free = match m.eq_of_var[v] {
            None => true,
            Some(other) => augment(incidence, m, other, visited),
        };
        if free {
            m.var_of_eq[e] = Some(v);
            m.eq_of_var[v] = Some(e);
            return true;
        }
    }
    false
}

/// The derivatives reachable from an unmatched derivative by alternating paths (each can be
/// the one left without an equation, by swapping along the path), and the equations on those
/// paths, both ascending.
fn undetermined(incidence: &[Vec<usize>], m: &Matching) -> (Vec<usize>, Vec<usize>) {
    let mut vars: Vec<usize> = (0..m.eq_of_var.len())
        .filter(|&v| m.eq_of_var[v].is_none())
        .collect();
    let mut eqs: Vec<usize> = Vec::new();
    let mut k = 0;
    while k < vars.len() {
        let v = vars[k];
        for (e, contained) in incidence.iter().enumerate() {
            if !contained.contains(&v) || eqs.contains(&e) {
                continue;
            }
            eqs.push(e);
            if let Some(w) = m.var_of_eq[e] {
                if !vars.contains(&w) {
                    vars.push(w);
                }
            }
        }
        k += 1;
    }
    vars.sort_unstable();
    eqs.sort_unstable();
    (vars, eqs)
}

/// The equations reachable from the unmatched equation `start` by alternating paths, and the
/// derivatives they contain (all matched, and one fewer than the equations at least).
fn hall_set(incidence: &[Vec<usize>], m: &Matching, start: usize) -> (Vec<usize>, Vec<usize>) {
    let mut eqs = vec![start];
    let mut vars: Vec<usize> = Vec::new();
    let mut k = 0;
    while k < eqs.len() {
        for &v in &incidence[eqs[k]] {
            if vars.contains(&v) {
                continue;
            }
            vars.push(v);
            if let Some(e) = m.eq_of_var[v] {
                if !eqs.contains(&e) {
                    eqs.push(e);
                }
            }
        }
        k += 1;
    }
    eqs.sort_unstable();
    vars.sort_unstable();
    (eqs, vars)
}

/// Tarjan's strongly connected components of "the equation matched to `v` contains `w`",
/// emitted dependencies first.
fn tarjan_blocks(incidence: &[Vec<usize>], m: &Matching) -> Vec<Block> {
    struct State<'a> {
        incidence: &'a [Vec<usize>],
        m: &'a Matching,
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        out: Vec<Block>,
    }
    fn visit(s: &mut State, v: usize) {
        s.index[v] = Some(s.next);
        s.low[v] = s.next;
        s.next += 1;
        s.stack.push(v);
        s.on_stack[v] = true;
        let e = s.m.eq_of_var[v].unwrap_or_default();
        for &w in &s.incidence[e] {
            match s.index[w] {
                None => {
                    visit(s, w);
                    s.low[v] = s.low[v].min(s.low[w]);
                }
                Some(iw) if s.on_stack[w] => s.low[v] = s.low[v].min(iw),
                Some(_) => {}
            }
        }
        if Some(s.low[v]) == s.index[v] {
            let mut vars = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack[w] = false;
                vars.push(w);
                if w == v {
                    break;
                }
            }
            vars.sort_unstable();
            let mut equations: Vec<usize> = vars.iter().filter_map(|&w| s.m.eq_of_var[w]).collect();
            equations.sort_unstable();
            s.out.push(Block { equations, vars });
        }
    }
    let n = m.eq_of_var.len();
    let mut s = State {
        incidence,
        m,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if s.index[v].is_none() {
            visit(&mut s, v);
        }
    }
    s.out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangular_system_gives_one_by_one_blocks_in_order() {
        // e0: x2 ; e1: x0, x2 ; e2: x1, x0
        let inc = vec![vec![2], vec![0, 2], vec![1, 0]];
        let b = blocks(&inc, 3).unwrap();
        let vars: Vec<Vec<usize>> = b.iter().map(|b| b.vars.clone()).collect();
        assert_eq!(vars, vec![vec![2], vec![0], vec![1]]);
        assert_eq!(b[1].equations, vec![1]);
    }

    #[test]
    fn coupled_block_is_found() {
        // e0: x0,x1 ; e1: x0,x1 ; e2: x2,x0
        let inc = vec![vec![0, 1], vec![1, 0], vec![2, 0]];
        let b = blocks(&inc, 3).unwrap();
        assert_eq!(
            b,
            vec![
                Block {
                    equations: vec![0, 1],
                    vars: vec![0, 1]
                },
                Block {
                    equations: vec![2],
                    vars: vec![2]
                }
            ]
        );
    }

    #[test]
    fn unused_derivative_is_reported() {
        let inc = vec![vec![0], vec![0]];
        assert_eq!(blocks(&inc, 2), Err(StructureError::Unused(vec![1])));
    }

    #[test]
    fn hall_set_names_the_short_equations() {
        // e0: x0 ; e1: x0 ; e2: x1, x2 (x1 used by e2 only, x2 used)
        let inc = vec![vec![0], vec![0], vec![1, 2]];
        match blocks(&inc, 3) {
            Err(StructureError::Singular {
                surplus,
                equations,
                vars,
                undetermined,
            }) => {
                assert_eq!(surplus, Some(1));
                assert_eq!(equations, vec![0, 1]);
                assert_eq!(vars, vec![0]);
                // e2 alone holds x1 and x2: either can be the one left over.
                assert_eq!(undetermined, vec![1, 2]);
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn fewer_equations_leave_every_shared_derivative_undetermined() {
        // e0: x0, x1 ; e1: x2 — x0 and x1 share one equation.
        let inc = vec![vec![0, 1], vec![2]];
        assert_eq!(
            blocks(&inc, 3),
            Err(StructureError::Singular {
                surplus: None,
                equations: vec![0],
                vars: vec![0, 1],
                undetermined: vec![0, 1],
            })
        );
    }

    #[test]
    fn matching_needs_augmenting_paths() {
        // e0: x0, x1 ; e1: x0 — greedy would give e0->x0 and leave e1 unmatched.
        let inc = vec![vec![0, 1], vec![0]];
        let b = blocks(&inc, 2).unwrap();
        assert_eq!(b.len(), 2);
        assert_eq!(b[0].vars, vec![0]);
        assert_eq!(b[0].equations, vec![1]);
    }
}
