//! Scene files, run folders, CSV histories and PNG plots: the only library crate that touches
//! files. Scene files are documented for users in `docs/scene-format.md`.

mod geometry;
mod overview;
pub mod particle_map;
pub mod plot;
mod run;
mod scene;
mod scene_field_file;
mod scene_file;
mod scene_material;
mod scene_wall;
pub mod vtk;

pub use geometry::{fill_shape, hole_rings, sampled_cell_volumes, Shape, VOLUME_SUBSAMPLES};
pub use overview::{BodyOverview, SceneOverview};
pub use run::{
    check_output_dir, frame_of, run_model, run_scene, run_scene_to_dir, run_scene_with_frames,
    write_csv, FrameSink, Intervals, ProbeHistory, Progress, RunError, RunRecord,
};
pub use scene::{
    load_scene, load_scene_without_field_tables, parse_scene, DimensionModel, FieldTableSummary,
    OutputSpec, ProbeSpec, Scene, SceneError,
};
