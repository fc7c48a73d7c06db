model_macros::model! {
    mod m {
        states { x, y }
        equations {
            der(x) = 1;
            2 * der(x) = y;
        }
    }
}

fn main() {}
