// An error inside an included file: the compiler underlines only Rust source, so it stands at
// the `include` that read the file, naming the file (read as text, the same error is located
// in `include-rows.dsl` itself, line and column).
model_macros::model! {
    mod m {
        params { k = 1 }
        states { x, v }
        include "include-rows.dsl";
    }
}

fn main() {
    let _ = m::Model::default();
}
