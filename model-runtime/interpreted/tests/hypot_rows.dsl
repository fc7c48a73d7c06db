// `hypot` in a right-hand side, its Jacobian and outputs, with arguments whose signs and order
// the simplifier rewrites (`tests/suite/hypot.rs` reads these rows interpreted, compiled to
// machine code and compiled by `model!`).
equations {
    der(x) = hypot(x, y);
    der(y) = hypot(-k*y, x);
}
outputs {
    swapped = hypot(y, x);
    on_an_axis = hypot(x, 0);
    unsigned = hypot(abs(x), -y);
}
