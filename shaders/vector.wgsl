// Element-wise CG vector operations on the contact set C (mask = 1), f32, and the dot
// products that feed CG's scalars (shared/slots.wgsl).
//
// The kernels that read a slot or produce a sum run a fixed number of workgroups over the grid
// (a grid-stride loop), so that each workgroup adds a pending slot's partials once and each
// produces one partial. CG's scalars never leave the device: α = r·z / s·Ks and β are formed
// by the kernels that use them, from the partials of the dispatches that produced them.
//
// CPU twin: `jkrbem::backend::cpu::CpuBackend` (the same operations in f64).

// Must stay in sync with `VectorParams` in src/backend/gpu/backend.rs.
struct Params {
    // Elements nx·ny.
    n: u32,
    // Slots of a ratio's numerator and denominator, or copy_slot's source and destination.
    num: u32,
    den: u32,
    // Slot receiving a sum (dot, cg_update's r·r), or NO_SLOT.
    out: u32,
    // ±1 for axpy_ratio and copy_slot (which copies sign · slots[num]).
    sign: f32,
    // The approach d (residual), the fraction t (lerp), or under a CG guard the stopping
    // threshold tol² (xpay_ratio: stop once slots[out] ≤ tol²·slots[aux]).
    scalar: f32,
    // 1: part of a guarded CG batch (return at once once it has stopped).
    guarded: u32,
    // xpay_ratio under a guard: the slot of ‖(d − h)_C‖².
    aux: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> a: array<f32>;
@group(0) @binding(2) var<storage, read> b: array<f32>;
@group(0) @binding(3) var<storage, read_write> y: array<f32>;
@group(0) @binding(4) var<storage, read> mask: array<u32>;
// Indenter profile h (length).
@group(0) @binding(5) var<storage, read> profile: array<f32>;
// cg_update's second output (the residual r).
@group(0) @binding(6) var<storage, read_write> y2: array<f32>;

fn index(gid: vec3<u32>, nwg: vec3<u32>) -> u32 {
    return gid.x + gid.y * nwg.x * WG;
}

fn group_index(wid: vec3<u32>, nwg: vec3<u32>) -> u32 {
    return wid.x + wid.y * nwg.x;
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

// y = a + t·(b − a) on C, 0 off C.
@compute @workgroup_size(WG)
fn lerp(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>) {
    let i = index(gid, nwg);
    if i >= params.n {
        return;
    }
    y[i] = select(0.0, a[i] + params.scalar * (b[i] - a[i]), mask[i] != 0u);
}

// One CG step's updates with α = slots[num] / slots[den]: y (p) += α·a (s) and y2 (r) −= α·b
// (K s) on C; then the pending sum Σ_C r·r into slot `out`.
@compute @workgroup_size(WG)
fn cg_update(
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    if params.guarded != 0u && cg_halted(lid) {
        return;
    }
    let alpha = slot_ratio(lid, params.num, params.den);
    let group = group_index(wid, nwg);
    if params.guarded != 0u && group == 0u && lid == 0u {
        scalars[STEPS_SLOT] = bitcast<u32>(bitcast<f32>(scalars[STEPS_SLOT]) + 1.0);
    }
    let groups = nwg.x * nwg.y;
    var sum = 0.0;
    var carry = 0.0;
    for (var i = group * WG + lid; i < params.n; i += groups * WG) {
        if mask[i] != 0u {
            y[i] = y[i] + alpha * a[i];
            let r = y2[i] - alpha * b[i];
            y2[i] = r;
            let t = sum + (r * r - carry);
            carry = (t - sum) - (r * r - carry);
            sum = t;
        }
    }
    slot_partial(lid, params.out, sum, group, groups);
}

// y += sign · ratio · a on C.
@compute @workgroup_size(WG)
fn axpy_ratio(
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    let step = params.sign * slot_ratio(lid, params.num, params.den);
    let groups = nwg.x * nwg.y;
    for (var i = group_index(wid, nwg) * WG + lid; i < params.n; i += groups * WG) {
        if mask[i] != 0u {
            y[i] = y[i] + step * a[i];
        }
    }
}

// y = a + ratio · y on C, 0 off C. Under a CG guard, this ends the iteration: once
// slots[out] (r·r of the step just made) ≤ tol²·slots[aux] (‖(d − h)_C‖²), or is not finite,
// the batch stops.
@compute @workgroup_size(WG)
fn xpay_ratio(
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    if params.guarded != 0u && cg_halted(lid) {
        return;
    }
    let beta = slot_ratio(lid, params.num, params.den);
    let group = group_index(wid, nwg);
    let groups = nwg.x * nwg.y;
    for (var i = group * WG + lid; i < params.n; i += groups * WG) {
        y[i] = select(0.0, a[i] + beta * y[i], mask[i] != 0u);
    }
    if params.guarded != 0u {
        let rr = slot_value(lid, params.out);
        let bb = slot_value(lid, params.aux);
        if group == 0u && lid == 0u && (rr <= params.scalar * bb || non_finite(rr)) {
            scalars[HALT_SLOT] = bitcast<u32>(1.0);
        }
    }
}

// The pending sum Σ_C a·b into slot `out` (compensated per thread, pairwise per workgroup).
@compute @workgroup_size(WG)
fn dot_masked(
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    if params.guarded != 0u && cg_halted(lid) {
        return;
    }
    let group = group_index(wid, nwg);
    let groups = nwg.x * nwg.y;
    var sum = 0.0;
    var carry = 0.0;
    for (var i = group * WG + lid; i < params.n; i += groups * WG) {
        if mask[i] != 0u {
            let v = a[i] * b[i] - carry;
            let t = sum + v;
            carry = (t - sum) - v;
            sum = t;
        }
    }
    slot_partial(lid, params.out, sum, group, groups);
}

// Every pending slot gets its final value (one workgroup per slot), before the host reads them.
@compute @workgroup_size(WG)
fn finish_slots(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>) {
    let v = slot_value(lid, wid.x);
    if lid == 0u {
        slot_set(wid.x, v);
    }
}

// slots[den] = sign · slots[num] (one workgroup; num may be den).
@compute @workgroup_size(WG)
fn copy_slot(@builtin(local_invocation_index) lid: u32) {
    let v = params.sign * slot_value(lid, params.num);
    if lid == 0u {
        slot_set(params.den, v);
    }
}
