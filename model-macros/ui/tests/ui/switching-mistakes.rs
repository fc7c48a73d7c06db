model_macros::model! {
    mod ball {
        params { g = 9.81, e = 0.8 }
        states { h = 1.0, v }
        mode flying {
            equations { der(h) = v; der(v) = -g; }
            when impact: h < 0 { w = -e * v; }
            when hit: h < 0 -> nowhere;
        }
        mode resting { equations { der(h) = 0; der(v) = 0; } }
    }
}

fn main() {
    // The switched model's items still exist: no cascade.
    use model_runtime::SwitchedModel as _;
    let model = ball::Model::default();
    let _ = model.graph();
    let _ = (ball::INITIAL, ball::mode::flying, ball::MODE_NAMES, ball::state::h);
    let _ = ball::resting::Model::default();
}
