//! Makes the certification's table of the plane's shares again and checks it against the one
//! compiled in (`jkrbem::backend::certify::PLANE_SHARES`): the balayage of a unit load on the
//! discs of radius 40 and 56 elements less their centres, extrapolated as 2 w₅₆ − w₄₀.
//!
//! `cargo run --release --example plane_shares` (dense solves: about 5 minutes on 2 cores).
//! Exits with status 1 if an entry differs by more than 1e-12 relative.

use jkrbem::backend::certify::{plane_shares_from_discs, DISC_RADII, PLANE_SHARES};

fn main() {
    let (inner, outer) = DISC_RADII;
    println!(
        "the plane's shares, 2 w{outer} - w{inner} (discs of radius {inner} and {outer} elements):"
    );
    let made = plane_shares_from_discs();
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
