//! Makes the certification's table of the plane's shares again and checks it against the one
//! compiled in (`jkrbem::backend::certify::PLANE_SHARES`): −G(o)/G(0) of the plane's inverse
//! influence on the 4096 × 4096 periodic lattice, less the table's margin.
//!
//! `cargo run --release --example plane_shares` (a few seconds on 2 cores); with `-- --print`
//! it prints the table made as Rust. Exits with status 1 if an entry differs from the table by
//! more than 1e-12 relative.

use jkrbem::backend::certify::{
    plane_shares_on_lattice, PLANE_SHARES, TABLE_LATTICE, TABLE_MARGIN,
};

fn main() {
    let print = std::env::args().any(|a| a == "--print");
    let made: Vec<(i64, i64, f64)> = plane_shares_on_lattice(TABLE_LATTICE)
        .into_iter()
        .map(|(x, y, w)| (x, y, w * (1.0 - TABLE_MARGIN)))
        .collect();
    if print {
        println!(
            "pub const PLANE_SHARES: [(i64, i64, f64); {}] = [",
            made.len()
        );
        for (x, y, w) in &made {
            println!("    ({x}, {y}, {w:?}),");
        }
        println!("];");
        return;
    }
    println!(
        "the plane's shares on the {TABLE_LATTICE} × {TABLE_LATTICE} lattice, less {TABLE_MARGIN:e}:"
    );
    let mut worst = 0.0f64;
    for (x, y, w) in &made {
        let table = PLANE_SHARES
            .iter()
            .find(|&&(a, b, _)| (a, b) == (*x, *y))
            .map(|e| e.2);
        let rel = table.map_or(f64::INFINITY, |t| (w / t - 1.0).abs());
        worst = worst.max(rel);
        println!("  ({x}, {y}): {w:.17e}  relative difference to the table {rel:.1e}");
    }
    if made.len() != PLANE_SHARES.len() || worst > 1e-12 {
        eprintln!(
            "plane_shares: the table does not match ({} entries made, {} tabled, worst relative difference {worst:.1e})",
            made.len(),
            PLANE_SHARES.len()
        );
        std::process::exit(1);
    }
    println!(
        "all {} entries match the table (worst relative difference {worst:.1e})",
        made.len()
    );
}
