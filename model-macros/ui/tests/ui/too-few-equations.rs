model_macros::model! {
    mod m {
        states { x, y }
        equations { der(x) = y; }
    }
}

fn main() {}
