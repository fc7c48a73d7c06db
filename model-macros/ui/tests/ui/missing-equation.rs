model_macros::model! {
    mod m {
        states { x, v, w }
        equations {
            der(x) = v;
            der(v) + der(w) = -x;
        }
    }
}

fn main() {
    // The failed model still defines everything a caller uses: no second error.
    let model = m::Model::default();
    let _ = model.params;
}
