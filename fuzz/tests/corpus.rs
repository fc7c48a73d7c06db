//! Every seed of every target passes its target's check: the regression tests of the
//! findings (a fixed finding is copied into its target's corpus), and a check that the seeds
//! themselves are inputs a target accepts without a finding.

use eulerdisk_fuzz::rng::Rng;
use eulerdisk_fuzz::targets::ALL;

#[test]
fn every_seed_passes_its_targets_check() {
    for target in ALL {
        assert!(!target.seeds().is_empty(), "{}: no seeds", target.name());
        for (k, seed) in target.seeds().iter().enumerate() {
            if let Err(wrong) = target.check(seed) {
                panic!("{} seed {k}: {wrong}\n{seed}", target.name());
            }
        }
    }
}

#[test]
fn a_targets_inputs_are_a_function_of_seed_and_index() {
    for target in ALL {
        let make = |index| target.input(&mut Rng::for_input(5, index));
        assert_eq!(make(17), make(17), "{}", target.name());
        assert_ne!(make(17), make(18), "{}", target.name());
    }
}
