//! The generator's random numbers, defined bit for bit by their algorithms so that a seed
//! gives the same surface on every machine and with every version of the crates below.
//!
//! - The uniform stream is `pcg64` (PCG-XSL-RR 128/64, an LCG modulo 2^128 with O'Neill's
//!   multiplier), built with `Pcg64::new(seed, PCG_STREAM)`: the seed is the LCG's initial
//!   state and the stream PCG's default one. rand_pcg's `new` follows PCG's reference
//!   `pcg64_srandom_r(seed, stream)`; the seeding helpers of `rand_core` are not used.
//! - A uniform number in (0, 1] or [0, 1) is the top 53 bits of one 64-bit output.
//! - Normal numbers come from the Box–Muller transform written here, not from a
//!   distribution crate: two uniforms `u1` in (0, 1] and `u2` in [0, 1) give
//!   `√(−2 ln u1)·cos(2π u2)` and `√(−2 ln u1)·sin(2π u2)`, in that order. (`ln`, `cos` and
//!   `sin` are the platform's, each within an ulp or so of the exact value.)

use rand_pcg::rand_core::Rng;
use rand_pcg::Pcg64;
use std::f64::consts::PI;

/// PCG's default stream (increment selector) for `pcg64`.
pub const PCG_STREAM: u128 = 0x0a02_bdbf_7bb3_c0a7_ac28_fa16_a64a_bf96;

/// 2^−53: the spacing of the 53-bit uniform numbers.
const UNIT: f64 = 1.0 / (1u64 << 53) as f64;

/// Standard normal numbers from a seed.
pub struct Normals {
    /// The uniform stream.
    rng: Pcg64,
}

impl Normals {
    /// The stream of `seed`.
    pub fn new(seed: u64) -> Self {
        Normals {
            rng: Pcg64::new(u128::from(seed), PCG_STREAM),
        }
    }

    /// The next 64-bit output of the uniform stream.
    pub fn next_u64(&mut self) -> u64 {
        self.rng.next_u64()
    }

    /// The next pair of independent standard normal numbers (mean 0, variance 1), from two
    /// outputs of the stream.
    pub fn pair(&mut self) -> (f64, f64) {
        let u1 = ((self.next_u64() >> 11) + 1) as f64 * UNIT;
        let u2 = (self.next_u64() >> 11) as f64 * UNIT;
        let r = (-2.0 * u1.ln()).sqrt();
        let (s, c) = (2.0 * PI * u2).sin_cos();
        (r * c, r * s)
    }
}
