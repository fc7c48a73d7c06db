model_macros::model! {
    mod m {
        states { x }
        equations { sin(der(x)) = x; }
    }
}

fn main() {}
