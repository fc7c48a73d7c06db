//! Output files: written atomically, as CSV or Parquet (`format`), from one table of cells
//! (`cells`) or streamed (the trajectory).

pub mod atomic;
pub mod cells;
pub mod files;
pub mod format;
#[cfg(feature = "parquet")]
pub mod parquet;
#[cfg(not(feature = "parquet"))]
#[path = "parquet_absent.rs"]
pub mod parquet;
pub mod tables;
