model_macros::model! {
    mod m {
        states { x }
        equations { der(x) = 1; }
        outputs {
            a = b + 1;
            b = x;
        }
    }
}

fn main() {}
