/// A chain of sines 64 deep under `der(..)`: the product rule makes each entry of its
/// Jacobian a triangular sum, which the factoring of common factors once nested in n³.
mod chain {
    params { k = 0.5 }
    states { x, y }
    equations {
        der(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(x))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))) = -k*y*x;
        der(y) = x;
    }
}
