/// A pendulum with every kind of item.
pub mod pend {
    params { m = 1.0, l = 1.0, g = 9.81, c = 0.0 }
    states { phi, omega }
    let x = l * sin(phi);
    let y = -l * cos(phi);
    equations {
        kinematics: der(phi) = omega;
        balance: m * l^2 * der(omega) + m*l*cos(phi)*0*der(phi) = -m * g * x - c*sign(omega);
    }
    outputs {
        energy = m / 2 * (l * omega)^2 + m * g * y;
        power = der(energy);
        side = if(phi >= 0, max(x, y), sign(omega) * min(x, der(omega)));
        angle = atan2(y, x) + sqrt(abs(x)) + exp(-t) + ln(2 + tan(phi)^2);
    }
    variant small { keep { omega } fix { m = 1, c = 0 } }
    chart scaled { states { w } replace { omega } let omega = 2*w; }
    options { swell_bound = 600, pivot_tolerance = 1e-12 }
}
