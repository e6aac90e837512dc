//! Batches of any scenes: a table with one scene per row and any parameter of the schema as a
//! column ([`table`]), each scene simulated to its own files, one shard of the rows at a time
//! if asked, resumable ([`run`]), the scenes run one after another or several at a time
//! ([`pool`], also what Python's `jkrbem.batch` runs in memory), and the scenes' summaries
//! merged into one table ([`collect`]).

pub mod collect;
pub mod pool;
pub mod run;
pub mod table;
