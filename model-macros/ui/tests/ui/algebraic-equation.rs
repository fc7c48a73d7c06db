model_macros::model! {
    mod m {
        params { l = 1.0 }
        states { x, y }
        equations {
            der(x) = y;
            circle: x^2 + y^2 = l^2;
        }
    }
}

fn main() {}
