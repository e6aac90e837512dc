// Element-wise CG vector operations on the contact set C (mask = 1), f32.
//
// CG's scalars live in the device buffer `slots`; ratio(num, den) = slots[num] / slots[den],
// 0 when the denominator is 0 (so the first CG direction is s = z). The host never reads
// α or β. CPU twin: `jkrbem::backend::cpu::CpuBackend` (the same operations in f64).

// Must stay in sync with `VectorParams` in src/backend/gpu/backend.rs.
struct Params {
    // Elements nx·ny.
    n: u32,
    // Slots of the ratio's numerator and denominator (axpy_ratio, xpay_ratio), or the source
    // (num) and destination (den) of copy_slot.
    num: u32,
    den: u32,
    pad0: u32,
    // ±1 for axpy_ratio.
    sign: f32,
    // The approach d (residual) or the fraction t (lerp).
    scalar: f32,
    pad1: u32,
    pad2: u32,
}

const WG: u32 = 256u;

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> a: array<f32>;
@group(0) @binding(2) var<storage, read> b: array<f32>;
@group(0) @binding(3) var<storage, read_write> y: array<f32>;
@group(0) @binding(4) var<storage, read> mask: array<u32>;
// Indenter profile h (length).
@group(0) @binding(5) var<storage, read> profile: array<f32>;
@group(0) @binding(6) var<storage, read_write> slots: array<f32>;

fn index(gid: vec3<u32>, nwg: vec3<u32>) -> u32 {
    return gid.x + gid.y * nwg.x * WG;
}

fn ratio() -> f32 {
    let d = slots[params.den];
    return select(slots[params.num] / d, 0.0, d == 0.0);
}

// y = d − h − a on C (a = u), 0 off C.
@compute @workgroup_size(WG)
fn residual(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>) {
    let i = index(gid, nwg);
    if i >= params.n {
        return;
    }
    y[i] = select(0.0, params.scalar - profile[i] - a[i], mask[i] != 0u);
}

// y += sign · ratio · a on C.
@compute @workgroup_size(WG)
fn axpy_ratio(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>) {
    let i = index(gid, nwg);
    if i >= params.n || mask[i] == 0u {
        return;
    }
    y[i] = y[i] + params.sign * ratio() * a[i];
}

// y = a + ratio · y on C, 0 off C.
@compute @workgroup_size(WG)
fn xpay_ratio(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>) {
    let i = index(gid, nwg);
    if i >= params.n {
        return;
    }
    y[i] = select(0.0, a[i] + ratio() * y[i], mask[i] != 0u);
}

// y = a + t·(b − a) on C, 0 off C.
@compute @workgroup_size(WG)
fn lerp(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>) {
    let i = index(gid, nwg);
    if i >= params.n {
        return;
    }
    y[i] = select(0.0, a[i] + params.scalar * (b[i] - a[i]), mask[i] != 0u);
}

// slots[den] = slots[num].
@compute @workgroup_size(1)
fn copy_slot() {
    slots[params.den] = slots[params.num];
}
