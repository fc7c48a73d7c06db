model_macros::model! {
    mod m {
        states { x, y }
        equations {
            a: der(x) = * y;
            b: der(y) = x +;
        }
    }
}

fn main() {}
