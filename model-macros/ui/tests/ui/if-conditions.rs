model_macros::model! {
    mod m {
        states { x, v }
        equations {
            der(x) = if(v == 0, 0, v);
            der(v) = -x;
        }
    }
}

model_macros::model! {
    mod n {
        states { x, v }
        equations {
            der(x) = v;
            2 * der(v) + if(der(x) > 0, 1, -1) = max(der(v), 0) + sign(der(x));
        }
    }
}

fn main() {}
