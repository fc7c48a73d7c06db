model_macros::model! {
    mod m {
        states { x }
        let a = b + x;
        let b = c;
        let c = a * 2;
        equations { der(x) = a; }
    }
}

fn main() {}
