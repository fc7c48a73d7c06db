model_macros::model! {
    mod m {
        states { x }
        equations { der(x) = sine(x); }
    }
}

fn main() {}
