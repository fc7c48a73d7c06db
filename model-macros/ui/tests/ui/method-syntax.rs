model_macros::model! {
    mod m {
        states { x, v }
        equations {
            der(x) = v;
            der(v) = -x.sin();
        }
    }
}

fn main() {
    use model_runtime::Model as _;
    let mut dy = [0.0; m::N_STATES];
    let _ = m::Model::new([]).rhs(0.0, &[0.0, 1.0], &mut dy);
}
