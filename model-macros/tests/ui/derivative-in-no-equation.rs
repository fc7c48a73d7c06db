model_macros::model! {
    mod m {
        states { x, y }
        equations {
            der(x) = 1;
            x = y;
        }
    }
}

fn main() {}
