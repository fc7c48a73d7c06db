/// A mass on a spring, dragged by a belt through Coulomb friction: it sticks to the belt until
/// the spring's pull exceeds static friction, slips back under kinetic friction, and sticks
/// again once it matches the belt's speed.
mod stick_slip {
    params {
        /// Mass (kg).
        m = 1.0,
        /// Spring stiffness (N/m); the spring's other end is fixed at x = 0.
        k = 10.0,
        /// Belt speed (m/s).
        vb = 0.5,
        /// Static friction coefficient.
        mu_s = 0.6,
        /// Kinetic friction coefficient.
        mu_k = 0.4,
        /// Gravity (m/s^2).
        g = 9.81,
    }
    states {
        /// Position (m).
        x = 0.0,
        /// Velocity (m/s).
        v = 0.5,
        /// Direction of the slip, the sign of v - vb while slipping (0 while stuck).
        s = 0.0,
    }

    outputs {
        /// The spring's force on the mass (N).
        spring = -k * x;
    }

    /// Carried by the belt: static friction holds the mass as long as it can.
    mode stuck {
        equations { der(x) = vb; der(v) = 0; der(s) = 0; }
        /// The spring pulls back harder than static friction holds: the mass slips back.
        when slip_back: k * x > mu_s * m * g -> slipping { s = -1; }
        /// The spring pushes ahead harder than static friction holds.
        when slip_ahead: k * x < -mu_s * m * g -> slipping { s = 1; }
    }

    /// Sliding on the belt under kinetic friction.
    mode slipping {
        equations {
            der(x) = v;
            m * der(v) = -k * x - mu_k * m * g * s;
            der(s) = 0;
        }
        /// The mass matches the belt's speed again: it sticks.
        when stick: s * (v - vb) < 0 -> stuck { v = vb; s = 0; }
    }
}
