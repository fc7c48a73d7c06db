/// A ball dropped on a hard floor: free flight, an impact that reverses and scales its
/// velocity, and rest once the bounces accumulate.
mod bouncing_ball {
    params {
        /// Gravity (m/s^2).
        g = 9.81,
        /// Coefficient of restitution.
        e = 0.8,
    }
    states {
        /// Height above the floor (m).
        h = 1.0,
        /// Upward velocity (m/s).
        v = 0.0,
    }

    mode flying {
        equations { der(h) = v; der(v) = -g; }
        /// The ball reaches the floor: its velocity reverses, scaled by the restitution.
        when impact: h < 0 { v = -e * v; }
        /// Ever shorter bounces end at a finite time: from there the ball lies on the floor.
        when impact accumulates -> resting { h = 0; v = 0; }
    }

    /// On the floor: nothing moves.
    mode resting {
        equations { der(h) = 0; der(v) = 0; }
    }

    outputs {
        energy = g * h + v^2 / 2;
    }
}
