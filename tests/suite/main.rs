//! Every integration test of the command line in one test binary, one module per former file: one
//! link instead of one per file, which is most of a cold `cargo test`.

mod architecture;
mod cli_eval;
mod cli_model;
mod cli_model_diagnostics;
mod cli_model_runs;
mod cli_run;
mod cli_switched;
mod extrema;
mod imports;
mod limits;
mod outputs;
mod paper_reference;
#[cfg(feature = "parquet")]
mod parquet_output;
mod pruned_scene;
mod quiet_run;
mod readme_commands;
mod run_pipeline;
mod scene_physics;
mod scenes;
mod sound;
mod sweep;
