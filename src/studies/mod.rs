//! The studies, each built on the session: a sweep over R1/R2 (`sweep`), crossed cylinders,
//! the whole study of the paper (`study`), reference ladders and their coverage, an accuracy
//! run's plan and estimate (`accuracy`), the closed-form curves and the charts' data, timings
//! (`bench`), and `collect`, which merges a split sweep's or a batch's shards.

pub mod accuracy;
pub mod bench;
pub mod chart_data;
pub mod collect;
pub mod coverage;
pub mod crossed;
pub mod curves;
pub mod reference;
pub mod study;
pub mod sweep;
