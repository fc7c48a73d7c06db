//! Models of any size run in exactly their own states: a chain of twenty pendulum links (40
//! states, past any fixed size) keeps its energy and solves its equations, and a model of
//! three states follows its closed form at the request's own tolerance.

use crate::{compile, model, tight};
use model_interpreted::{evaluate, solve, ModelFile, SolveRequest, Stop};
use model_runtime::Method;

const LINKS: usize = 20;

/// The example chain of twenty links (`model-macros/examples/pendulum_chain.dsl`).
fn chain() -> ModelFile {
    let text = include_str!("../../../../model-macros/examples/pendulum_chain.dsl");
    compile("pendulum_chain.dsl", text)
}

/// A bent chain at rest: link `i` at `0.6 sin(i)` from the vertical.
fn bent() -> Vec<f64> {
    let mut y = vec![0.0; 2 * LINKS];
    for (i, q) in y[..LINKS].iter_mut().enumerate() {
        *q = 0.6 * ((i + 1) as f64).sin();
    }
    y
}

/// `c_ij = 21 - max(i, j)` (1-based): the masses link `max(i, j)` carries.
fn c(i: usize, j: usize) -> f64 {
    (LINKS - i.max(j)) as f64
}

#[test]
fn the_chain_solves_lagranges_equations_at_a_moving_state() {
    let file = chain();
    let compiled = file.smooth(None).unwrap();
    assert_eq!(compiled.states.len(), 2 * LINKS);
    let mut y = bent();
    for (i, w) in y[LINKS..].iter_mut().enumerate() {
        *w = 0.4 * ((2 * i) as f64).cos();
    }
    let (m, l, g) = (1.0, 1.0, 9.81);
    let values = evaluate(compiled, 0.0, &y, &[m, l, g]).unwrap();
    let (q, w) = y.split_at(LINKS);
    let acc: Vec<f64> = (1..=LINKS)
        .map(|k| values.derivatives.get(&format!("der(w{k})")).unwrap())
        .collect();
    // Each link's equation, by hand: sum_j c_ij cos(q_i - q_j) a_j
    // = -sum_j c_ij sin(q_i - q_j) w_j^2 - (g / l) c_ii sin(q_i).
    for i in 0..LINKS {
        let inertia: f64 = (0..LINKS)
            .map(|j| c(i, j) * (q[i] - q[j]).cos() * acc[j])
            .sum();
        let force: f64 = -(0..LINKS)
            .map(|j| c(i, j) * (q[i] - q[j]).sin() * w[j] * w[j])
            .sum::<f64>()
            - g / l * c(i, i) * q[i].sin();
        let scale: f64 = (0..LINKS).map(|j| c(i, j) * acc[j].abs()).sum::<f64>() + force.abs();
        assert!(
            (inertia - force).abs() <= 1e-12 * scale,
            "link {}: {inertia} vs {force}",
            i + 1
        );
    }
    for k in 1..=LINKS {
        assert_eq!(
            values.derivatives.get(&format!("der(q{k})")),
            Some(w[k - 1])
        );
    }
}

#[test]
fn the_chain_runs_in_its_own_forty_states_and_keeps_its_energy() {
    let file = chain();
    let states = &file.smooth(None).unwrap().states;
    let request = SolveRequest {
        method: Method::Dop853,
        dt: Some(0.05),
        state: states.iter().cloned().zip(bent()).collect(),
        ..tight(SolveRequest::new(1.0))
    };
    let solved = solve(model(&file), &request).unwrap();
    assert_eq!(solved.states, 2 * LINKS);
    assert_eq!(solved.columns.len(), 1 + 2 * LINKS + 1);
    assert_eq!(solved.stop, Stop::EndTime);
    assert_eq!(solved.len(), 21);
    let energy = solved.column("energy").unwrap();
    let e0 = energy[0];
    // At rest: the potential alone, -(g / l) sum_i c_ii cos(q_i).
    let potential: f64 = -9.81
        * (0..LINKS)
            .map(|i| c(i, i) * (0.6 * ((i + 1) as f64).sin()).cos())
            .sum::<f64>();
    assert!(
        (e0 - potential).abs() <= 1e-12 * potential.abs(),
        "{e0} vs {potential}"
    );
    let drift = energy.iter().map(|e| (e - e0).abs()).fold(0.0, f64::max);
    assert!(drift <= 1e-9 * e0.abs(), "energy drifts by {drift} of {e0}");
    // It moved: the chain falls.
    let last = solved.last_row().unwrap();
    assert!(last[1 + LINKS..1 + 2 * LINKS].iter().any(|w| w.abs() > 0.1));
}

#[test]
fn a_model_of_three_states_follows_its_closed_form() {
    let file = compile(
        "three.dsl",
        "mod three {
            params { w = 2, k = 0.5 }
            states { x, y, z }
            equations { der(x) = -w * y; der(y) = w * x; der(z) = -k * z; }
        }",
    );
    for method in [Method::Dopri5, Method::Dop853, Method::Rodas4] {
        let request = SolveRequest {
            method,
            times: Some(vec![0.5, 1.0, 2.5]),
            state: vec![("x".into(), 1.0), ("z".into(), 3.0)],
            ..tight(SolveRequest::new(2.5))
        };
        let solved = solve(model(&file), &request).unwrap();
        assert_eq!(solved.states, 3);
        assert_eq!(solved.len(), 3);
        // Rodas4 is of order 4 with a dense output of order 3: looser than the explicit pair.
        let within = if method == Method::Rodas4 {
            1e-7
        } else {
            1e-10
        };
        for row in solved.trajectory.rows() {
            let t = row[0];
            let exact = [(2.0 * t).cos(), (2.0 * t).sin(), 3.0 * (-0.5 * t).exp()];
            for (got, want) in row[1..4].iter().zip(exact) {
                assert!(
                    (got - want).abs() <= within,
                    "{method:?} t = {t}: {got} vs {want}"
                );
            }
        }
    }
}
