model_macros::model! {
    mod m {
        params { k }
        states { x }
        equations { der(x) = k; }
        variant small { keep { y } }
    }
}

fn main() {}
