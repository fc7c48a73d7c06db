model_macros::model! {
    mod m {
        states { x, y, z }
        equations {
            first: der(x) = 1;
            second: 2 * der(x) = y;
            third: der(y) + der(z) = 0;
        }
    }
}

fn main() {}
