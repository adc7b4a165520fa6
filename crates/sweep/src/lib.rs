//! A study beyond one machine: a sweep spec ([`spec`]) names scenes, techniques, resolutions,
//! partitions, filters, light directions and camera poses; its [`cells`] are every frame (scene ×
//! camera × light) times every combination, each with an estimated cost; a [`shard`] of N runs a
//! cost-balanced share of them ([`run`]), storing each cell's result ([`record`]) in a sweep
//! directory ([`store`]) as it finishes, so reruns resume; [`merge`] gathers every shard's cells
//! into one table (CSV and Parquet, [`table`]) and one report, the same whether the sweep ran as
//! one shard or many.

pub mod cells;
pub mod error;
pub mod frames;
pub mod merge;
pub mod record;
pub mod run;
pub mod shard;
pub mod spec;
pub mod store;
pub mod table;

pub use cells::Plan;
pub use error::SweepError;
pub use record::CellRecord;
pub use shard::Shard;
pub use spec::{EXAMPLE, Spec};
pub use store::{SweepDir, SweepIdentity};
