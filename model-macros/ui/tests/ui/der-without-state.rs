model_macros::model! {
    mod m {
        params { k }
        states { x }
        let c = 2 * k;
        equations { der(x) + der(c * pi) = 0; }
    }
}

fn main() {}
