model_macros::model! {
    mod m {
        params { w = 2*pi, k = 1.0 }
        states { x }
        equations { der(x) = -k * w * x; }
    }
}

fn main() {
    // `w` and `k` keep their places, so the named and array forms still resolve.
    let _ = m::Params { k: 2.0, ..Default::default() };
    let _ = m::param::w;
}
