model_macros::model! {
    mod m {
        states { x }
        equations {
            der(x) = 1;
            der(x) = 2;
        }
    }
}

fn main() {}
