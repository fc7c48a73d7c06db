model_macros::model! {
    mod m {
        states { x, t }
        let sin = x;
        equations { der(x) = 1; der(t) = 1; }
    }
}

fn main() {}
