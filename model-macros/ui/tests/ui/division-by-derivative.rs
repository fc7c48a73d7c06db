model_macros::model! {
    mod m {
        states { x }
        equations { 1 / der(x) = x; }
    }
}

fn main() {}
