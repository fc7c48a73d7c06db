// The disk of the smooth models: its parameters (the paper's values, the air at rest by
// default), its moments of inertia and the air's drag coefficients, which the rows of
// box1_rolling.dsl and box3_sliding.dsl read (docs/physics.md §2). The disk's mode graph
// (../hybrid/switching.rs) defines these names itself, the same way, with parameters of its
// own that a run holds at still air.
params { m = 0.4387, a = 0.03755, g = 9.81, mu_d = 0.115, mu_st = 0.2, mu_a = 0.0, w_z = 0.0 }

let A = m*a^2/4;
let C = m*a^2/2;
let k_F = mu_a*pi*a^2;
let k_M = mu_a*pi*a^4/4;
