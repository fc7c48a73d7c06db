model_macros::model! {
    mod m {
        params { k }
        states { x, y }
        equations {
            der(x) = q;
            der(y) = foo(x) + der(k);
        }
        variant v { keep { w } }
    }
}

fn main() {}
