model_macros::model! {
    mod m {
        params { k = 2.0, c = 0.1 }
        states { x, v }
        equations {
            der(x) = v;
            der(v) = -k * undefined - c * v;
        }
        outputs { energy = (v^2 + k * x^2) / 2; }
        variant undamped { keep { x } fix { c = 0.0 } }
    }
}

fn main() {
    // The failed model still defines every public item a caller uses: only the model's own
    // error is reported.
    use model_runtime::{Model as _, WithOutputs as _};
    let model = m::Model::from_params(m::Params { k: 3.0, ..Default::default() });
    let y = m::State { x: 1.0, v: 0.0 }.to_array();
    let mut dy = [0.0; m::N_STATES];
    let _ = model.rhs(0.0, &y, &mut dy);
    let _ = model.evaluate(0.0, &y).map(|ev| m::Outputs::from(ev.outputs).energy);
    let _ = (m::state::x, m::param::k, m::output::energy, &m::INFO.name);
    let _ = m::undamped::Model::default().params[m::undamped::param::k];
}
