//! The WGSL modules of the GPU backend and the explicit bind group layout of each of their
//! kernels. Each module is its own file in `shaders/` preceded by the shared files it uses
//! from `shaders/shared/` (WGSL has no imports, so they are joined here at compile time;
//! nothing is patched as text). A test checks every layout against what naga finds that the
//! kernel uses.

use super::recorder::Binding::{self, Read, ReadWrite, Uniform};

/// A kernel (a module's entry point) and the group-0 bindings it uses.
#[derive(Debug, Clone, Copy)]
pub struct KernelLayout {
    /// The WGSL entry point.
    pub entry: &'static str,
    /// (binding, what it holds), in binding order.
    pub bindings: &'static [(u32, Binding)],
}

/// The kernels of both spectral variants.
pub const SPECTRAL_KERNELS: &[KernelLayout] = &[
    KernelLayout {
        entry: "rows_forward",
        bindings: &[
            (1, Read),
            (2, Read),
            (3, ReadWrite),
            (4, Read),
            (8, ReadWrite),
            (9, Read),
        ],
    },
    KernelLayout {
        entry: "columns",
        bindings: &[
            (0, Uniform),
            (3, ReadWrite),
            (4, Read),
            (5, Read),
            (8, ReadWrite),
        ],
    },
    KernelLayout {
        entry: "rows_inverse",
        bindings: &[
            (0, Uniform),
            (2, Read),
            (3, ReadWrite),
            (4, Read),
            (6, ReadWrite),
            (7, Read),
            (8, ReadWrite),
        ],
    },
    KernelLayout {
        entry: "fft_lines",
        bindings: &[(0, Uniform), (3, ReadWrite), (4, Read)],
    },
];

/// The kernels of vector.wgsl.
pub const VECTOR_KERNELS: &[KernelLayout] = &[
    KernelLayout {
        entry: "residual",
        bindings: &[
            (0, Uniform),
            (1, Read),
            (3, ReadWrite),
            (4, Read),
            (5, Read),
        ],
    },
    KernelLayout {
        entry: "lerp",
        bindings: &[
            (0, Uniform),
            (1, Read),
            (2, Read),
            (3, ReadWrite),
            (4, Read),
        ],
    },
    KernelLayout {
        entry: "cg_update",
        bindings: &[
            (0, Uniform),
            (1, Read),
            (2, Read),
            (3, ReadWrite),
            (4, Read),
            (6, ReadWrite),
            (8, ReadWrite),
        ],
    },
    KernelLayout {
        entry: "axpy_ratio",
        bindings: &[
            (0, Uniform),
            (1, Read),
            (3, ReadWrite),
            (4, Read),
            (8, ReadWrite),
        ],
    },
    KernelLayout {
        entry: "xpay_ratio",
        bindings: &[
            (0, Uniform),
            (1, Read),
            (3, ReadWrite),
            (4, Read),
            (8, ReadWrite),
        ],
    },
    KernelLayout {
        entry: "dot_masked",
        bindings: &[
            (0, Uniform),
            (1, Read),
            (2, Read),
            (4, Read),
            (8, ReadWrite),
        ],
    },
    KernelLayout {
        entry: "finish_slots",
        bindings: &[(8, ReadWrite)],
    },
    KernelLayout {
        entry: "copy_slot",
        bindings: &[(0, Uniform), (8, ReadWrite)],
    },
];

/// The kernels of reduce.wgsl.
pub const REDUCE_KERNELS: &[KernelLayout] = &[
    KernelLayout {
        entry: "measure_partials",
        bindings: &[
            (0, Uniform),
            (1, Read),
            (3, Read),
            (4, ReadWrite),
            (5, ReadWrite),
        ],
    },
    KernelLayout {
        entry: "crossing_partials",
        bindings: &[
            (0, Uniform),
            (1, Read),
            (2, Read),
            (3, Read),
            (4, ReadWrite),
        ],
    },
    KernelLayout {
        entry: "max_abs_partials",
        bindings: &[(0, Uniform), (1, Read), (3, Read), (4, ReadWrite)],
    },
    KernelLayout {
        entry: "finish_measure",
        bindings: &[(0, Uniform), (4, ReadWrite), (5, ReadWrite), (8, ReadWrite)],
    },
    KernelLayout {
        entry: "finish_min",
        bindings: &[(0, Uniform), (4, ReadWrite), (8, ReadWrite)],
    },
];

/// The kernel of contact.wgsl.
pub const CONTACT_KERNELS: &[KernelLayout] = &[KernelLayout {
    entry: "update_contact",
    bindings: &[
        (0, Uniform),
        (1, ReadWrite),
        (2, Read),
        (3, ReadWrite),
        (4, Read),
        (5, ReadWrite),
    ],
}];

/// The kernel of spread.wgsl.
pub const SPREAD_KERNELS: &[KernelLayout] = &[KernelLayout {
    entry: "spread_detached",
    bindings: &[
        (0, Uniform),
        (1, ReadWrite),
        (2, Read),
        (3, Read),
        (4, Read),
    ],
}];

/// The kernels of certify.wgsl.
pub const CERTIFY_KERNELS: &[KernelLayout] = &[
    KernelLayout {
        entry: "seed",
        bindings: &[(0, Uniform), (2, Read), (3, ReadWrite), (4, ReadWrite)],
    },
    KernelLayout {
        entry: "mark",
        bindings: &[
            (0, Uniform),
            (3, ReadWrite),
            (4, ReadWrite),
            (5, ReadWrite),
            (9, ReadWrite),
            (10, ReadWrite),
        ],
    },
    KernelLayout {
        entry: "tiles",
        bindings: &[(0, Uniform), (9, ReadWrite), (11, ReadWrite)],
    },
    KernelLayout {
        entry: "jacobi",
        bindings: &[
            (0, Uniform),
            (2, Read),
            (4, ReadWrite),
            (5, ReadWrite),
            (6, Read),
            (7, ReadWrite),
            (8, Read),
            (9, ReadWrite),
        ],
    },
    KernelLayout {
        entry: "certify",
        bindings: &[
            (0, Uniform),
            (1, ReadWrite),
            (2, Read),
            (3, ReadWrite),
            (4, ReadWrite),
            (5, ReadWrite),
            (6, Read),
            (8, Read),
            (9, ReadWrite),
        ],
    },
];

/// The bindings of `entry` in `kernels`. Panics if it is not there (a programming error that
/// every GPU test would show).
pub fn bindings(kernels: &[KernelLayout], entry: &str) -> &'static [(u32, Binding)] {
    kernels
        .iter()
        .find(|k| k.entry == entry)
        .unwrap_or_else(|| panic!("no layout for kernel {entry}"))
        .bindings
}

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

/// A cascade round's predicted start.
pub const SPREAD: &str = concat!(
    include_str!("../../../shaders/shared/common.wgsl"),
    include_str!("../../../shaders/spread.wgsl"),
);

/// Detachments certain before a solve.
pub const CERTIFY: &str = concat!(
    include_str!("../../../shaders/shared/common.wgsl"),
    include_str!("../../../shaders/certify.wgsl"),
);

/// Every module, by the name of its own file, with its kernels: what a validation test
/// compiles and checks.
pub const MODULES: [(&str, &str, &[KernelLayout]); 7] = [
    ("spectral.wgsl (2048)", SPECTRAL_2048, SPECTRAL_KERNELS),
    ("spectral.wgsl (4096)", SPECTRAL_4096, SPECTRAL_KERNELS),
    ("vector.wgsl", VECTOR, VECTOR_KERNELS),
    ("reduce.wgsl", REDUCE, REDUCE_KERNELS),
    ("contact.wgsl", CONTACT, CONTACT_KERNELS),
    ("spread.wgsl", SPREAD, SPREAD_KERNELS),
    ("certify.wgsl", CERTIFY, CERTIFY_KERNELS),
];
