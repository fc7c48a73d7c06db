// Rows included by `include-error-inside.rs`: `c` is not a name of the model.
equations {
    der(x) = v;
    der(v) = -k*x - c*v;
}
