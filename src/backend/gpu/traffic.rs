//! Device-memory traffic of the GPU backend's kernels.
//!
//! Two different counts:
//! - what each kernel moves, read off its WGSL (every load and store of device memory, whole
//!   fields where a kernel reads a field under the contact mask, since the memory system moves
//!   whole sectors around the contact's edge; the adds of pending partial sums that every
//!   workgroup of a consumer makes; twiddle-table loads, which stay in the cache, are left
//!   out). The recorder adds these up per dispatch: [`crate::backend::Counters::bytes`].
//! - the floor of one CG iteration: what its operations must move at the least, each reading
//!   its inputs once and writing its outputs once, with a 2-D FFT's half spectrum written and
//!   read once at each of its two pass boundaries and its symbol read once
//!   ([`cg_iteration_floor`]). Setting a measured time against the floor at the card's
//!   bandwidth tells how far from bandwidth-bound a kernel runs.

/// Bytes of an f32 field of n elements (or of its u32 mask).
fn field(n: usize) -> u64 {
    4 * n as u64
}

/// Bytes of a filter's half spectrum: (L + 1)·ny complex f32, L = nx padded, nx/2 periodic.
pub fn half_spectrum(nx: usize, ny: usize, padded: bool) -> u64 {
    let l = if padded { nx } else { nx / 2 };
    8 * ((l + 1) * ny) as u64
}

/// Bytes of a filter's symbol on the device: (L + 1)·my real f32.
pub fn symbol(nx: usize, ny: usize, padded: bool) -> u64 {
    let (l, my) = if padded { (nx, 2 * ny) } else { (nx / 2, ny) };
    4 * ((l + 1) * my) as u64
}

/// What each pass of one spectral filter moves (bytes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SpectralBytes {
    /// Reads the field (and the mask when masked), writes the half spectrum.
    pub rows_forward: u64,
    /// Reads and writes the half spectrum, reads the symbol.
    pub columns: u64,
    /// Reads the half spectrum (and the mask when masked, and the dot's other factor),
    /// writes the field (and one partial per workgroup).
    pub rows_inverse: u64,
}

impl SpectralBytes {
    /// All three passes.
    pub fn total(&self) -> u64 {
        self.rows_forward + self.columns + self.rows_inverse
    }
}

/// What the three passes of a spectral filter on nx × ny data move (see the module notes).
pub fn spectral_passes(
    nx: usize,
    ny: usize,
    padded: bool,
    masked: bool,
    dot: bool,
) -> SpectralBytes {
    let n = nx * ny;
    let spec = half_spectrum(nx, ny, padded);
    let mask = if masked { field(n) } else { 0 };
    let partials = if dot { 4 * ny as u64 + 4 } else { 0 };
    SpectralBytes {
        rows_forward: field(n) + mask + spec,
        columns: 2 * spec + symbol(nx, ny, padded),
        rows_inverse: spec + mask + field(n) + if dot { field(n) } else { 0 } + partials,
    }
}

/// Workgroups of the grid-stride kernels (update, direction, dot) on n elements: at least 8
/// elements per thread, at most 1024 workgroups (one partial sum each).
pub fn stride_groups(n: usize) -> u32 {
    n.div_ceil(256 * 8).clamp(1, 1024) as u32
}

/// Bytes every workgroup of a consumer reads to add a pending slot of `partials` partials.
pub fn slot_reads(groups: u32, partials: u32) -> u64 {
    4 * groups as u64 * partials as u64
}

/// What `cg_update` moves on n elements: reads p, s, r, q and the mask, writes p and r, adds
/// two pending slots of `partials` partials each, writes its own partials.
pub fn cg_update(n: usize, partials: u32) -> u64 {
    let g = stride_groups(n);
    7 * field(n) + 2 * slot_reads(g, partials) + 4 * g as u64
}

/// What `xpay_ratio` moves: reads z, s and the mask, writes s, adds two pending slots.
pub fn xpay_ratio(n: usize, partials: u32) -> u64 {
    4 * field(n) + 2 * slot_reads(stride_groups(n), partials)
}

/// What `axpy_ratio` moves: reads x, y and the mask, writes y, adds two pending slots.
pub fn axpy_ratio(n: usize, partials: u32) -> u64 {
    4 * field(n) + 2 * slot_reads(stride_groups(n), partials)
}

/// What `dot_masked` moves: reads a, b and the mask, writes its partials.
pub fn dot(n: usize) -> u64 {
    3 * field(n) + 4 * stride_groups(n) as u64
}

/// What an element-wise kernel of `fields` field reads and writes moves (residual, lerp).
pub fn elementwise(n: usize, fields: u64) -> u64 {
    fields * field(n)
}

/// The floor of one CG iteration on an nx × ny grid (bytes): the convolution q = K s
/// (reads s, writes q, its padded half spectrum twice written and read, its symbol), the
/// update (reads p, s, r, q and the mask, writes p and r), the preconditioner z = M r when
/// `preconditioned` (reads r and the mask, writes z, its periodic half spectrum and symbol;
/// otherwise a copy of r), and the new direction (reads z and s, writes s). The dot products
/// fuse into these passes and add nothing.
pub fn cg_iteration_floor(nx: usize, ny: usize, preconditioned: bool) -> u64 {
    let n = nx * ny;
    let filter = |padded: bool| 4 * half_spectrum(nx, ny, padded) + symbol(nx, ny, padded);
    let convolution = 2 * field(n) + filter(true);
    let update = 7 * field(n);
    let preconditioner = if preconditioned {
        3 * field(n) + filter(false)
    } else {
        2 * field(n)
    };
    let direction = 3 * field(n);
    convolution + update + preconditioner + direction
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_floor_grows_with_the_grid_and_is_of_order_half_a_gigabyte_at_2048() {
        let small = cg_iteration_floor(1024, 1024, true);
        let large = cg_iteration_floor(2048, 2048, true);
        assert!(
            (3.9..4.1).contains(&(large as f64 / small as f64)),
            "{large} vs {small}"
        );
        assert!((4e8..6e8).contains(&(large as f64)), "{large}");
    }
}
