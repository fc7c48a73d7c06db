model_macros::model! {
    mod m {
        states { x }
        equations { der(x) = atan2(x) + sin(x, x); }
        outputs { r = hypot(x, x, x); }
    }
}

fn main() {}
