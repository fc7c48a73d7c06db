//! Every integration test of the disk in one test binary, one module per former file: one
//! link instead of one per file, which is most of a cold `cargo test`.

mod charts;
mod common;
mod error_norm;
mod extrema_scan;
mod extremes_flat;
mod extremes_friction;
mod extremes_input;
mod extremes_slip;
mod extremes_spin;
mod extremes_tolerance;
mod extremes_upright;
mod generated_vs_reference;
mod graph_engine;
mod hybrid_paper;
mod hybrid_states;
mod invariants;
mod jacobian;
mod linear_stability;
mod located_extrema;
mod misprint;
mod normal_force;
mod output_failure;
mod paper_scene;
mod pruned_run;
mod reference_vs_explicit;
mod scene_settings;
mod singular;
mod switched_disk;
mod trailing;
mod trajectories;
mod variants;
