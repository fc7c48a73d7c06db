/// A body dropped from rest: height `h`, velocity `v`, gravity `g`. The smallest model file;
/// `eulerdisk model solve model-macros/examples/drop.dsl --state h=2 --t-end 5 --event h:down:stop`
/// stops it on the ground at t = sqrt(2 h / g).
mod drop {
    params { g = 9.81 }
    states { h, v }
    equations { der(h) = v; der(v) = -g; }
}
