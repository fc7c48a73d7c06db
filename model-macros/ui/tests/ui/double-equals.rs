model_macros::model! {
    mod m {
        states { x }
        equations { der(x) == -x; }
    }
}

fn main() {}
