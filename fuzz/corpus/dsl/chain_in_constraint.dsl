/// A fuzzing find, 121 sines deep (here 24, to keep the seed fast): a chain inside the
/// derivative of a constraint took seconds to compile (the factoring rebuilt every sum it
/// looked at, and each rebuild searched every term for `sin^2 + cos^2`).
mod m {
    params { m = 1.5, g = 9.81 }
    states { x, y, vx, vy, P }
    equations {
        kx: der(x) = vx;
        ky: der(y) = vy;
        mx: m*der(vx) = -der(P)*x;
        my: m*der(vy) = -der(P)*y - m*g;
        c: der(x*vx +sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin( y*vy))))))))))))))))))))))))) = 0;
    }
    outputs { lambda = der(P); energystates = m/2*(vx^2 + vy^2) + m*g*y; }
}
