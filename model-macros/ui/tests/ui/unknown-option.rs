model_macros::model! {
    mod m {
        states { x }
        equations { der(x) = 1; }
        options { swell_limit = 10 }
    }
}

fn main() {}
