//! The device's scalar registers (shaders/shared/slots.wgsl): CG's scalars, whose value may be
//! pending as per-workgroup partial sums until a kernel that reads them adds them up.

/// Slots on the device, handed out by `Scalars::slot` up to [`HALT_SLOT`]. Must equal
/// `SLOTS` in shaders/shared/slots.wgsl.
pub const SLOTS: usize = 64;
/// Partials one slot can hold (the most workgroups a producing kernel may run). Must equal
/// `MAX_PARTIALS` in shaders/shared/slots.wgsl.
pub const MAX_PARTIALS: usize = 4096;
/// The slot that turns 1.0 once a guarded CG batch has stopped on the device (`HALT_SLOT`).
pub const HALT_SLOT: usize = 62;
/// The slot counting the CG steps of a guarded batch (`STEPS_SLOT`, an f32 count).
pub const STEPS_SLOT: usize = 63;
/// "No slot" (`NO_SLOT` in the shaders).
pub const NO_SLOT: u32 = u32::MAX;

/// Bytes of the `scalars` buffer: values, pending counts and every slot's partials.
pub const fn scalars_bytes() -> u64 {
    4 * (2 * SLOTS + SLOTS * MAX_PARTIALS) as u64
}

/// Byte offset of slot `s`'s value in the `scalars` buffer.
pub const fn value_offset(s: usize) -> u64 {
    4 * s as u64
}
