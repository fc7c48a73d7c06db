model_macros::model! {
    mod m {
        params { k = 2.0 }
        states { x }
        equations { der(x) = -k * x**3; }
    }
}

fn main() {
    let _ = m::Model::new([1.0]);
}
