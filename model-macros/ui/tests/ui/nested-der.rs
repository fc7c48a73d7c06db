model_macros::model! {
    mod m {
        states { x }
        let v = der(x);
        equations { der(v) = 1; }
    }
}

fn main() {}
