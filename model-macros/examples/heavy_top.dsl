// A heavy symmetric top in Euler angles (z-x-z): what goes inside `model! { .. }`.
// `eulerdisk model show model-macros/examples/heavy_top.dsl`, `model eval`, `model solve` read it as it is.
/// A symmetric top spinning on a fixed tip; `l` is the tip-to-centre-of-mass distance,
/// `I1` the moment of inertia about a transverse axis through the tip, `I3` about the
/// symmetry axis.
pub mod heavy_top {
    params { m = 0.5, g = 9.81, l = 0.04, I1 = 0.0012, I3 = 0.0009 }
    // A sound start (the top tilted, spinning fast, precessing slowly), not the singular
    // point theta = 0 of the Euler angles; `--state` or `state=` start it elsewhere.
    states { phi, theta = 0.3, psi, w_phi = 2, w_theta, w_psi = 150 }

    // The spin about the symmetry axis, and the momenta conjugate to phi and psi.
    let omega3 = w_psi + w_phi * cos(theta);
    let p_psi = I3 * omega3;
    let p_phi = I1 * w_phi * sin(theta)^2 + p_psi * cos(theta);

    equations {
        der(phi) = w_phi;
        der(theta) = w_theta;
        der(psi) = w_psi;
        precession: der(p_phi) = 0;
        spin: der(p_psi) = 0;
        nutation: I1 * der(w_theta) = I1 * w_phi^2 * sin(theta) * cos(theta)
            - I3 * omega3 * w_phi * sin(theta) + m * g * l * sin(theta);
    }

    outputs {
        energy = I1 / 2 * (w_theta^2 + w_phi^2 * sin(theta)^2) + I3 / 2 * omega3^2
            + m * g * l * cos(theta);
        momentum_phi = p_phi;
        momentum_psi = p_psi;
    }
}
