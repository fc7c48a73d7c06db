model_macros::model! {
    mod m {
        params { k }
        states { x }
        equations { der(x) + der(k) = 0; }
    }
}

fn main() {}
