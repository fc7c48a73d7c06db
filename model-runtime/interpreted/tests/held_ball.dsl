/// A dropped ball that falls in its downward speed `w` (in the slot of its velocity `v`),
/// counts its bounces and records an echo 0.1 s after each, from the time of the last bounce
/// it holds.
mod ball {
    params { g = 9.81, e = 0.8 }
    states { h = 1.0, v = 0.0 }
    discrete { bounces = 0, t_last = -1 }
    mode falling {
        states { w } replace { v }
        equations { der(h) = -w; der(w) = g; }
        when impact: h < 0 -> rising { v = e * w; bounces = bounces + 1; t_last = t; }
    }
    mode rising {
        equations { der(h) = v; der(v) = -g; }
        first_step = abs(v / der(v)) / 100;
        when apex: v < 0 -> falling { w = -v; }
        when echo: t > t_last + 0.1;
    }
}
