model_macros::model! {
    mod m {
        states { x }
        equations { der(x) = undefined; }
    }
}

fn main() {
    // The failed model still defines `m::Model`: only the model's own error is reported.
    let _model = m::Model;
}
