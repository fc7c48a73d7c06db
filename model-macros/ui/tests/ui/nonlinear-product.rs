model_macros::model! {
    mod m {
        states { x, y }
        equations {
            der(x) * der(y) = 1;
            der(y) = x;
        }
    }
}

fn main() {}
