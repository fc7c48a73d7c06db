//! Output files: written atomically, as CSV or Parquet (`format`), from one table of cells
//! (`cells`) or streamed (the trajectory).

pub mod atomic;
pub mod cells;
pub mod files;
pub mod format;
pub mod parquet;
pub mod tables;
