/// A slender rigid block rocking on a hard floor (Housner's model, for small angles): it tips
/// about one bottom corner, hits the floor with the other, loses angular velocity at each
/// impact, and comes to stand once its ever shorter rocks accumulate.
mod rocking_block {
    params {
        /// Frequency parameter sqrt(3 g / (4 R)) (1/s), R the half-diagonal.
        p = 2.0,
        /// Slenderness: the angle between the diagonal and the vertical (rad).
        alpha = 0.2,
        /// Ratio of the angular velocities after and before an impact.
        r = 0.7,
    }
    states {
        /// Tilt (rad), positive when the block rocks on its right corner.
        theta = 0.1,
        /// Angular velocity (rad/s).
        omega = 0.0,
    }

    mode rocking {
        equations {
            der(theta) = omega;
            // Gravity's torque about the corner in contact, linearised: it pulls the block back
            // upright as long as |theta| < alpha.
            der(omega) = p^2 * (theta - alpha * sign(theta));
        }
        /// The block lands flat and tips over onto its other corner, losing angular velocity.
        when impact: theta == 0 { omega = r * omega; }
        /// The rocks accumulate: the block stands.
        when impact accumulates -> standing { theta = 0; omega = 0; }
        /// Past its corner the block falls over.
        when overturns: abs(theta) > alpha -> stop;
    }

    /// Standing upright on the floor.
    mode standing {
        equations { der(theta) = 0; der(omega) = 0; }
    }
}
