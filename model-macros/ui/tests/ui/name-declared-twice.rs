model_macros::model! {
    mod m {
        params { k }
        states { x, k }
        equations { der(x) = 1; der(k) = 1; }
    }
}

fn main() {}
