//! Integration tests of `cdpr`, compiled as one test binary (one link instead of
//! one per file). Each module is one former `tests/*.rs` file.

mod api_cli;
mod cable_model_cli;
mod calibrate_cli;
mod cli;
mod common;
mod convert_cli;
mod dynamics_cli;
mod interference_cli;
mod orientations_cli;
mod plots;
mod polytope_cli;
mod pulley_cli;
mod robot_files;
mod robot_plot_cli;
mod trajectory;
mod viewer;
mod workspace_cli;
mod workspace_mesh_cli;
