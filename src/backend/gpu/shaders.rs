//! The WGSL modules of the GPU backend. Each module is its own file in `shaders/` preceded by
//! the shared files it uses from `shaders/shared/` (WGSL has no imports, so they are joined
//! here at compile time; nothing is patched as text).

/// Workgroup size (`WG`).
pub const COMMON: &str = include_str!("../../../shaders/shared/common.wgsl");
/// Device scalar slots with pending partial sums.
pub const SLOTS: &str = include_str!("../../../shaders/shared/slots.wgsl");
/// The workgroup-memory FFT.
pub const FFT: &str = include_str!("../../../shaders/shared/fft.wgsl");

/// The spectral filter's three passes and the line FFT, for lines of up to 2048 values
/// (8 per thread).
pub const SPECTRAL_2048: &str = concat!(
    include_str!("../../../shaders/shared/common.wgsl"),
    include_str!("../../../shaders/shared/points_2048.wgsl"),
    include_str!("../../../shaders/shared/slots.wgsl"),
    include_str!("../../../shaders/shared/fft.wgsl"),
    include_str!("../../../shaders/spectral.wgsl"),
);

/// The same for lines of up to 4096 values (16 per thread; more registers, used only for
/// grids whose sides need it).
pub const SPECTRAL_4096: &str = concat!(
    include_str!("../../../shaders/shared/common.wgsl"),
    include_str!("../../../shaders/shared/points_4096.wgsl"),
    include_str!("../../../shaders/shared/slots.wgsl"),
    include_str!("../../../shaders/shared/fft.wgsl"),
    include_str!("../../../shaders/spectral.wgsl"),
);

/// CG's element-wise operations and dot products.
pub const VECTOR: &str = concat!(
    include_str!("../../../shaders/shared/common.wgsl"),
    include_str!("../../../shaders/shared/slots.wgsl"),
    include_str!("../../../shaders/vector.wgsl"),
);

/// Per-state reductions (total pressure and count, first crossing).
pub const REDUCE: &str = concat!(
    include_str!("../../../shaders/shared/common.wgsl"),
    include_str!("../../../shaders/shared/slots.wgsl"),
    include_str!("../../../shaders/reduce.wgsl"),
);

/// The Pohrt–Popov contact sweep.
pub const CONTACT: &str = concat!(
    include_str!("../../../shaders/shared/common.wgsl"),
    include_str!("../../../shaders/contact.wgsl"),
);

/// Every module, by the name of its own file: what a validation test compiles.
pub const MODULES: [(&str, &str); 5] = [
    ("spectral.wgsl (2048)", SPECTRAL_2048),
    ("spectral.wgsl (4096)", SPECTRAL_4096),
    ("vector.wgsl", VECTOR),
    ("reduce.wgsl", REDUCE),
    ("contact.wgsl", CONTACT),
];
