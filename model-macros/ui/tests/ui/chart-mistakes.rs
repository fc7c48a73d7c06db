model_macros::model! {
    mod m {
        params { k = 1.0 }
        states { x, y }
        equations { der(x) = y; der(y) = -k * x; }
        outputs { energy = x^2 + y^2; }
        chart polar {
            states { r, phi } replace { x, z }
            let y = r * sin(phi);
            outputs after power { radius = r; }
        }
        chart m { states { a, b } replace { x, y } let x = a; let y = b; }
    }
}

fn main() {
    // The model and its valid-looking chart still exist: no cascade.
    let _ = m::Model::default();
    let _ = polar::Model::default();
}
