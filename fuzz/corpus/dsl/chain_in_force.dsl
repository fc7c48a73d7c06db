/// A fuzzing find, 232 sines deep (here 24, to keep the seed fast): a chain under `der(..)` in
/// a force of a constrained system took 54 s to compile (the factoring's n^3, then the
/// differentiation's search for `sin^2 + cos^2`, which cost every term its factors squared).
mod m {
    params { m = 1.5, g = 9.81 }
    states { x, y, vx, vy, P }
    equations {
        kx: der(x) = vx;
        ky: der(y) = vy;
        mx: m*der(vx) = -der(P)*x;
        my: m*der(vy) = -der(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(P)*y ))))))))))))))))))))))))- m*g;
        c: der(x*vx + y*vy) = 0;
    }
    outputs { lambda = der(P); energy = m/2*(vx^2 + vy^2) + m*g*y; }
}
