//! The flat evaluator against the reference interpreter, to the bit, on random models (their
//! right-hand sides, Jacobians and outputs reading `dy`) at random points, failures included.

use proptest::prelude::*;

use super::props::ast;
use super::random_models::{point, random_model, spec};
use crate::eval::{EvalFailure, Inputs};
use crate::spec::{Named, NodeId};
use crate::{compile, CompileOptions, FlatModel, FlatProgram, Program};

/// `program` run both ways at `inputs`; the stores (as the sink sees them) or the failures
/// must be identical, bit for bit.
pub(super) fn same_as_reference(
    program: &Program,
    flat: &FlatProgram,
    inputs: &Inputs,
    dense: impl Fn(&crate::Stores) -> Vec<f64>,
) -> Result<(), TestCaseError> {
    let mut out = vec![f64::NAN; flat.sink.len()];
    let got = flat.run(inputs, &mut flat.scratch(), &mut out);
    match (program.eval(inputs), got) {
        (Ok(stores), Ok(())) => {
            let want = dense(&stores);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            prop_assert_eq!(
                bits(&out),
                bits(&want),
                "{:?} vs {:?}\n{}",
                out,
                want,
                program
            );
        }
        (
            Err(EvalFailure::SingularPivot { text: a, value: x }),
            Err(EvalFailure::SingularPivot { text: b, value: y }),
        ) => {
            prop_assert_eq!(a, b);
            prop_assert_eq!(x.to_bits(), y.to_bits());
        }
        (want, got) => prop_assert!(false, "reference {:?}, flat {:?}", want, got),
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn flat_programs_match_the_reference_bit_for_bit(
        model in random_model(),
        outputs in prop::collection::vec(ast(true, true), 0..3),
        v in point(),
        scale in prop::sample::select(vec![1.0, -1.0, 0.0, 1e-300, 1e300]),
    ) {
        let mut spec = spec(&model);
        spec.outputs = outputs.into_iter().enumerate().map(|(k, value)| Named {
            name: format!("o{k}"),
            id: NodeId(60 + k as u32),
            value,
        }).collect();
        let Ok(compiled) = compile(&spec, &CompileOptions::default()) else {
            return Ok(());
        };
        let n = model.n;
        let flat = FlatModel::new(&compiled, 1).expect("a compiled model lays out");
        // Ordinary points and extreme ones (zeros, huge, tiny, negative), where pivots fail
        // and values overflow: the failures must agree too.
        let states: Vec<f64> = [v[0], v[1], v[3]][..n].iter().map(|x| x * scale).collect();
        let params = [v[2]];
        let inputs = Inputs { t: 0.5, states: &states, params: &params, ders: &[] };
        same_as_reference(&compiled.rhs, &flat.rhs, &inputs, |s| s.ders(n))?;
        same_as_reference(&compiled.jacobian, &flat.jacobian, &inputs, |s| {
            s.jacobian(n).concat()
        })?;
        let ders: Vec<f64> = states.iter().map(|x| 0.5 - x).collect();
        let inputs = Inputs { ders: &ders, ..inputs };
        let m = compiled.outputs.len();
        same_as_reference(&compiled.outputs_program, &flat.outputs, &inputs, |s| s.outputs(m))?;
    }
}
