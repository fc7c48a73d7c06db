//! `hypot` is `f64::hypot` to the bit in every engine: the same rows read at run time (the
//! reference interpreter, the flat evaluator and the machine code compiled from it) and
//! compiled by `model!`, over arguments from zero and subnormals to the largest finite values,
//! of both signs. Where the call overflows, every engine sees the same infinity.

use crate::compile;
use model_algebra::{CompiledModel, FlatProgram, Inputs, Program, Shape, Sink};
use model_runtime::{Model, WithOutputs};

model_macros::model! {
    mod hypot_rows {
        params { k = 3 }
        states { x, y }
        include "../hypot_rows.dsl";
    }
}

/// The same model, read at run time.
fn interpreted() -> CompiledModel {
    let text = format!(
        "mod hypot_rows {{ params {{ k = 3 }} states {{ x, y }} {} }}",
        include_str!("../hypot_rows.dsl")
    );
    let file = compile("hypot_rows.dsl", &text);
    file.smooth(None).unwrap().clone()
}

/// Arguments over the whole range: zeros, subnormals, the extremes, and random magnitudes
/// (a fixed xorshift sequence), each with both signs.
fn arguments() -> Vec<f64> {
    let mut values = vec![
        0.0, 1.0, 3.0, 4.0, 0.1, 1e300, 1e-300, 5e-324, 1e-310, 1.7e308, 1e154, 1e-162,
    ];
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    for _ in 0..24 {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let mantissa = 1.0 + (state >> 12) as f64 / (1u64 << 52) as f64;
        values.push(mantissa * 10f64.powi((state % 601) as i32 - 300));
    }
    let negated: Vec<f64> = values.iter().map(|v| -v).collect();
    values.extend(negated);
    values
}

/// `program` at `inputs` by the reference interpreter, the flat evaluator and the machine
/// code (where the host has a code generator), which must agree to the bit; the values.
fn run_everywhere(program: &Program, shape: Shape, sink: Sink, inputs: &Inputs) -> Vec<f64> {
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let stores = program.eval(inputs).unwrap();
    let want = match sink {
        Sink::Ders(n) => stores.ders(n),
        Sink::Outputs(n) => stores.outputs(n),
        Sink::Jacobian(n) => stores.jacobian(n).concat(),
    };
    let flat = FlatProgram::new(program, shape, sink).unwrap();
    let mut out = vec![f64::NAN; sink.len()];
    flat.run(inputs, &mut flat.scratch(), &mut out).unwrap();
    assert_eq!(bits(&out), bits(&want), "flat evaluator at {inputs:?}");
    match model_jit::JitProgram::new(flat.clone()) {
        Ok(jit) => {
            let mut out = vec![f64::NAN; sink.len()];
            jit.run(inputs, &mut flat.scratch(), &mut out).unwrap();
            assert_eq!(bits(&out), bits(&want), "machine code at {inputs:?}");
        }
        // Only where Cranelift has no backend for the host.
        Err(model_jit::JitError::Unsupported(why)) => {
            if cfg!(any(target_arch = "x86_64", target_arch = "aarch64")) {
                panic!("{why}");
            }
        }
        Err(e) => panic!("{e}"),
    }
    want
}

#[test]
fn hypot_is_f64_hypot_to_the_bit_in_every_engine() {
    let model = interpreted();
    let compiled = hypot_rows::Model::new([3.0]);
    let (n, k) = (2, 3.0f64);
    let values = arguments();
    let mut overflowed = 0;
    for &x in &values {
        for &y in &values {
            let (y_, p) = ([x, y], [k]);
            let shape = Shape {
                states: n,
                params: 1,
                ders: 0,
            };
            let mut inputs = Inputs {
                t: 0.0,
                states: &y_,
                params: &p,
                ders: &[],
            };
            let ders = run_everywhere(&model.rhs, shape, Sink::Ders(n), &inputs);
            let want = [x.hypot(y), (-k * y).hypot(x)];
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&ders), bits(&want), "der at ({x:e}, {y:e})");
            run_everywhere(&model.jacobian, shape, Sink::Jacobian(n), &inputs);
            inputs.ders = &ders;
            let with_ders = Shape { ders: n, ..shape };
            let outputs =
                run_everywhere(&model.outputs_program, with_ders, Sink::Outputs(3), &inputs);
            let want_outputs = [y.hypot(x), x.hypot(0.0), x.abs().hypot(-y)];
            assert_eq!(
                bits(&outputs),
                bits(&want_outputs),
                "outputs at ({x:e}, {y:e})"
            );
            // The model compiled by `model!`: the same bits, or (where a derivative overflows)
            // its finiteness check.
            let mut dy = [0.0; 2];
            match Model::rhs(&compiled, 0.0, &[x, y], &mut dy) {
                Ok(()) => {
                    assert_eq!(bits(&dy), bits(&want), "model! der at ({x:e}, {y:e})");
                    let mut out = [0.0; 3];
                    WithOutputs::outputs(&compiled, 0.0, &[x, y], &dy, &mut out).unwrap();
                    assert_eq!(
                        bits(&out),
                        bits(&want_outputs),
                        "model! outputs at ({x:e}, {y:e})"
                    );
                }
                Err(e) => {
                    assert!(
                        want.iter().any(|v| v.is_infinite()),
                        "{e} at ({x:e}, {y:e})"
                    );
                    overflowed += 1;
                }
            }
        }
    }
    // The points where `3 y` overflows (`y = ±1.7e308`: two of the values, with every `x`)
    // fail; the rest evaluate.
    assert_eq!(overflowed, 2 * values.len());
}
