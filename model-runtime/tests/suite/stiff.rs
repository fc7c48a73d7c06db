//! The implicit method on stiff problems: far fewer steps than an explicit one, same answer.

use crate::common::VanDerPol;
use model_runtime::{integrate, Dop853, Dopri5, Rodas4, StepOptions, Tolerance};

#[test]
fn van_der_pol_mu_1000_is_cheap_for_rodas4() {
    let vdp = VanDerPol { mu: 1000.0 };
    let y0 = [2.0, 0.0];
    let t_end = 300.0;
    let tol = Tolerance::scalar(1e-7, 1e-7);
    let opts = StepOptions::default();
    let implicit = integrate(&vdp, Rodas4::new(), tol, opts, 0.0, &y0, t_end).unwrap();
    let explicit = integrate(&vdp, Dopri5::new(), tol, opts, 0.0, &y0, t_end).unwrap();
    println!("RODAS4 {:?}\nDOPRI5 {:?}", implicit.stats, explicit.stats);
    assert!(
        implicit.stats.steps * 50 < explicit.stats.steps,
        "RODAS4 {} steps vs DOPRI5 {}",
        implicit.stats.steps,
        explicit.stats.steps
    );
    assert_eq!(
        implicit.stats.jacobian_evals,
        implicit.stats.steps + implicit.stats.rejected
    );
    // Both solve the same problem: the slow manifold's position agrees.
    let reference = integrate(
        &vdp,
        Dop853::new(),
        Tolerance::scalar(1e-10, 1e-10),
        opts,
        0.0,
        &y0,
        t_end,
    )
    .unwrap();
    for sol in [&implicit, &explicit] {
        assert!(
            (sol.y[0] - reference.y[0]).abs() < 1e-4 * reference.y[0].abs(),
            "{:?} vs {:?}",
            sol.y,
            reference.y
        );
    }
}
