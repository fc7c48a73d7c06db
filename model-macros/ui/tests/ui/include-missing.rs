// An included file that is not there: refused at its path, which the message names.
model_macros::model! {
    mod m {
        states { x }
        include "no-such-rows.dsl";
        equations { der(x) = 1; }
    }
}

fn main() {
    let _ = m::Model::default();
}
