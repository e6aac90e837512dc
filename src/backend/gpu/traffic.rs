//! Device-memory traffic of the GPU backend's kernels, counted from their reads and writes:
//! what one CG iteration must move, to set its time against the card's bandwidth (the floor).

/// Longest FFT line held in workgroup memory (lines beyond it take global-memory stages).
const SHARED_LINE: usize = 2048;

/// Bytes one 2-D spectral filter moves: data nx × ny, transform mx × my, `masked` input and
/// output (the preconditioner).
pub fn spectral_filter_bytes(nx: usize, ny: usize, mx: usize, my: usize, masked: bool) -> u64 {
    let field = 4 * (nx * ny) as u64;
    let mask = if masked { field } else { 0 };
    let hx = (mx / 2) as u64;
    let rows = 8 * ny as u64 * hx;
    let cols = 8 * (hx + 1) * my as u64;
    let passes = |n: usize| 1 + (n / SHARED_LINE.min(n)).trailing_zeros() as u64;
    let row_fft = 2 * rows * passes(mx / 2);
    let col_fft = 2 * cols * passes(my);
    let pack = field + mask + rows;
    let split = rows + cols;
    let multiply = 2 * cols + cols / 2;
    let merge = cols * ny as u64 / my as u64 + rows;
    let unpack = rows + field + mask;
    pack + row_fft + split + col_fft + multiply + col_fft + merge + row_fft + unpack
}

/// Bytes one CG iteration moves on an nx × ny grid: the padded convolution, the
/// preconditioner (if any), three dot products (s·Ks, r·z and, at a check, r·r), two axpy and
/// one xpay update, each reading the contact mask.
pub fn cg_iteration_bytes(nx: usize, ny: usize, preconditioned: bool) -> u64 {
    let field = 4 * (nx * ny) as u64;
    let convolution = spectral_filter_bytes(nx, ny, 2 * nx, 2 * ny, false);
    let preconditioner = if preconditioned {
        spectral_filter_bytes(nx, ny, nx, ny, true)
    } else {
        2 * field
    };
    let dots = 3 * 3 * field;
    let updates = 3 * 4 * field;
    convolution + preconditioner + dots + updates
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn traffic_grows_with_the_grid_and_counts_global_stages() {
        let small = cg_iteration_bytes(1024, 1024, true);
        let large = cg_iteration_bytes(2048, 2048, true);
        // 4× the elements, plus one global FFT stage on the 4096-long columns at 2048².
        assert!(large > 4 * small, "{large} vs {small}");
        // At 2048² a preconditioned iteration moves on the order of 1 GB.
        assert!((5e8..3e9).contains(&(large as f64)), "{large}");
    }
}
