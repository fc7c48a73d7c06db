//! The flat evaluator against the reference interpreter, to the bit, on every program of every
//! example model (right-hand sides, Jacobians, outputs, guards, resets, first steps) and of the
//! disk's own models, at random states and parameters.

use model_algebra::{
    CompiledModel, EvalFailure, FlatProgram, Inputs, Program, Shape, Sink, Stores,
};
use model_interpreted::ModelFile;

/// One program of a model with what it is given and where it stores.
pub struct Case {
    /// `file: program`, for messages.
    pub name: String,
    pub program: Program,
    pub shape: Shape,
    pub sink: Sink,
}

/// The rhs, Jacobian and outputs of `model`, reading `params` parameters.
fn model_cases(file: &str, model: &CompiledModel, params: usize, out: &mut Vec<Case>) {
    let n = model.states.len();
    let shape = Shape {
        states: n,
        params,
        ders: 0,
    };
    let mut push = |what: &str, program: &Program, shape, sink| {
        out.push(Case {
            name: format!("{file}: {} {what}", model.name),
            program: program.clone(),
            shape,
            sink,
        })
    };
    push("rhs", &model.rhs, shape, Sink::Ders(n));
    push("jacobian", &model.jacobian, shape, Sink::Jacobian(n));
    let with_ders = Shape { ders: n, ..shape };
    push(
        "outputs",
        &model.outputs_program,
        with_ders,
        Sink::Outputs(model.outputs.len()),
    );
}

/// Every program of a model file.
pub fn cases(name: &str, file: &ModelFile) -> Vec<Case> {
    let mut out = Vec::new();
    match file {
        ModelFile::Smooth(models) => {
            for m in models {
                model_cases(name, &m.compiled, m.compiled.params.len(), &mut out);
            }
        }
        ModelFile::Switched(model) => {
            let params = model.n_params() + model.discrete.len();
            for mode in &model.modes {
                let m = &mode.model;
                model_cases(name, m, params, &mut out);
                let n = m.states.len();
                let shape = Shape {
                    states: n,
                    params,
                    ders: n,
                };
                let mut push = |what: String, program: &Program, k: usize| {
                    out.push(Case {
                        name: format!("{name}: {} {what}", m.name),
                        program: program.clone(),
                        shape,
                        sink: Sink::Outputs(k),
                    })
                };
                push("guards".into(), &mode.guards, mode.events.len());
                for event in &mode.events {
                    let jumps = match &event.action {
                        model_dsl::Action::Jump(jump) => Some(jump),
                        _ => None,
                    };
                    for jump in jumps.into_iter().chain(&event.accumulation) {
                        push(
                            format!("{} reset", event.name),
                            &jump.program,
                            jump.states.len(),
                        );
                    }
                }
                if let Some(step) = &mode.first_step {
                    push("first step".into(), &step.program, 1);
                }
            }
        }
    }
    out
}

/// Every example model and the disk's own, compiled.
pub fn example_files() -> Vec<(String, ModelFile)> {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let mut files = Vec::new();
    let mut paths: Vec<_> = std::fs::read_dir(format!("{root}/model-macros/examples"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "dsl"))
        .collect();
    paths.sort();
    for path in paths {
        let file = ModelFile::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        files.push((
            path.file_name().unwrap().to_string_lossy().into_owned(),
            file,
        ));
    }
    for name in ["box1_rolling.rs", "box3_sliding.rs"] {
        let path = format!("{root}/equations/src/models/{name}");
        let models = (model_dsl::Source::read(path.as_ref()).unwrap())
            .compile()
            .unwrap();
        files.push((name.to_string(), ModelFile::Smooth(models)));
    }
    assert!(files.len() >= 8, "examples found: {}", files.len());
    files
}

/// A small deterministic generator (xorshift), so that the points are the same every run.
pub struct Points(u64);

impl Points {
    pub fn new(seed: u64) -> Self {
        Points(seed | 1)
    }

    /// A value in `[-2, 2]`, sometimes an exact zero or one (where pivots fail and selects
    /// tie).
    pub fn value(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        match self.0 % 16 {
            0 => 0.0,
            1 => 1.0,
            _ => (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0,
        }
    }

    pub fn vec(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.value()).collect()
    }
}

/// The reference's stores as the sink sees them.
pub fn dense(stores: &Stores, sink: Sink) -> Vec<f64> {
    match sink {
        Sink::Ders(n) => stores.ders(n),
        Sink::Outputs(n) => stores.outputs(n),
        Sink::Jacobian(n) => stores.jacobian(n).concat(),
    }
}

/// The reference's result at `inputs`, as the sink sees it.
pub fn reference(case: &Case, inputs: &Inputs) -> Result<Vec<f64>, EvalFailure> {
    case.program.eval(inputs).map(|s| dense(&s, case.sink))
}

/// `got` and `want` are the same values to the bit, or the same failure.
pub fn assert_same(
    case: &Case,
    got: Result<Vec<f64>, EvalFailure>,
    want: Result<Vec<f64>, EvalFailure>,
) {
    let bits = |r: &Result<Vec<f64>, EvalFailure>| match r {
        Ok(v) => Ok(v.iter().map(|x| x.to_bits()).collect::<Vec<_>>()),
        Err(EvalFailure::SingularPivot { text, value }) => Err((text.clone(), value.to_bits())),
        Err(other) => panic!("{}: {other:?}", case.name),
    };
    assert_eq!(
        bits(&got),
        bits(&want),
        "{}: {got:?} vs {want:?}",
        case.name
    );
}

/// Runs `check` on every program of every example at random points (states, parameters,
/// derivatives, time); returns how many evaluations succeeded.
pub fn at_random_points(mut check: impl FnMut(&Case, &Inputs)) -> usize {
    let mut points = Points::new(35);
    let mut count = 0;
    for (name, file) in example_files() {
        for case in cases(&name, &file) {
            for _ in 0..50 {
                let (states, params, ders) = (
                    points.vec(case.shape.states),
                    points.vec(case.shape.params),
                    points.vec(case.shape.ders),
                );
                let inputs = Inputs {
                    t: points.value(),
                    states: &states,
                    params: &params,
                    ders: &ders,
                };
                count += reference(&case, &inputs).is_ok() as usize;
                check(&case, &inputs);
            }
        }
    }
    count
}

#[test]
fn the_flat_evaluator_matches_the_reference_on_every_example() {
    let mut scratches = 0;
    let ok = at_random_points(|case, inputs| {
        let flat = FlatProgram::new(&case.program, case.shape, case.sink)
            .unwrap_or_else(|e| panic!("{}: {e:?}", case.name));
        let mut out = vec![f64::NAN; case.sink.len()];
        let mut scratch = flat.scratch();
        scratches += 1;
        let got = flat
            .run(inputs, &mut scratch, &mut out)
            .map(|()| out.clone());
        assert_same(case, got, reference(case, inputs));
        // The same scratch again: nothing of the last call leaks into the next.
        let again = flat.run(inputs, &mut scratch, &mut out).map(|()| out);
        assert_same(case, again, reference(case, inputs));
    });
    // Most points evaluate (the failures compared are the exception, not the rule).
    assert!(
        ok * 2 > scratches,
        "{ok} of {scratches} evaluations succeeded"
    );
}

/// Machine code against the flat evaluator: the same values and failures, to the bit, on every
/// program of every example (where the machine has a code generator).
#[test]
fn compiled_programs_match_the_flat_evaluator_on_every_example() {
    let mut compiled = 0;
    // The points of one program come one after another: it is compiled once for them.
    let mut last: Option<(String, FlatProgram, model_jit::JitProgram)> = None;
    at_random_points(|case, inputs| {
        if last.as_ref().is_none_or(|(name, ..)| *name != case.name) {
            let flat = FlatProgram::new(&case.program, case.shape, case.sink).unwrap();
            last = match model_jit::JitProgram::new(flat.clone()) {
                Ok(jit) => Some((case.name.clone(), flat, jit)),
                Err(model_jit::JitError::Unsupported(_)) => None,
                Err(e) => panic!("{}: {e}", case.name),
            };
            compiled += last.is_some() as usize;
        }
        let Some((_, flat, jit)) = &last else {
            return;
        };
        let (mut a, mut b) = (
            vec![f64::NAN; case.sink.len()],
            vec![f64::NAN; case.sink.len()],
        );
        let mut scratch = flat.scratch();
        let want = flat.run(inputs, &mut scratch, &mut a).map(|()| a);
        let got = jit.run(inputs, &mut scratch, &mut b).map(|()| b);
        assert_same(case, got, want);
    });
    if cfg!(any(target_arch = "x86_64", target_arch = "aarch64")) {
        assert!(
            compiled > 0,
            "no program compiled on a machine Cranelift supports"
        );
    }
}

/// When (and whether) a model's programs are compiled never changes a solve: every example
/// file solved with the flat evaluator only, with every program compiled at its first
/// evaluation, and with each compiled part way through the run (after a few dozen
/// evaluations, so the run switches from one to the other), gives the same rows, events,
/// counts and failures, to the bit, with an explicit and an implicit method (whose Jacobian
/// is compiled too).
#[test]
fn the_evaluator_never_changes_a_solve() {
    use model_interpreted::{set_evaluator, solve, Evaluator, SolveRequest};
    use model_runtime::Method;
    let evaluators = [
        Evaluator::Flat,
        Evaluator::Compiled,
        Evaluator::Tiered { after: 37 },
        Evaluator::default(),
    ];
    let mut compared = 0;
    for (name, file) in example_files() {
        if name.ends_with(".rs") {
            continue; // The disk's models: their programs are compared above.
        }
        let model = file.model(None).unwrap();
        for method in [Method::Dop853, Method::Rodas4] {
            let mut request = SolveRequest::new(1.0);
            request.method = method;
            let solved: Vec<String> = (evaluators.iter())
                .map(|&evaluator| {
                    set_evaluator(evaluator);
                    format!("{:?}", solve(model, &request))
                })
                .collect();
            set_evaluator(Evaluator::default());
            for (evaluator, got) in evaluators.iter().zip(&solved).skip(1) {
                assert!(
                    *got == solved[0],
                    "{name}, {method:?}: {evaluator:?} differs from the flat evaluator"
                );
            }
            compared += solved[0].starts_with("Ok") as usize;
        }
    }
    assert!(compared >= 8, "{compared} solves compared");
}
