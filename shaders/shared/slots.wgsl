// Shared by every kernel that reads or writes CG's scalars: device-side scalar registers
// ("slots") whose value may still be pending as per-workgroup partial sums.
//
// A kernel that produces a sum (a dot product fused into a transform or an update) writes one
// partial per workgroup and, from its workgroup 0, the number of partials; the slot's value is
// then "pending". A kernel that consumes the slot adds the partials itself, every workgroup in
// the same fixed order (so all of them see the same value), at the start of its work. This
// saves the separate one-workgroup "finish" dispatch of a classic two-pass reduction. The host
// finishes pending slots (`finish_slots`) before it reads them.
//
// Layout of `scalars` (u32 words; values are f32 bits):
//   [0, SLOTS)                          the slots' values
//   [SLOTS, 2·SLOTS)                    pending partial counts (0: the value is final)
//   [2·SLOTS + s·MAX_PARTIALS + g)      partial g of slot s
// Must stay in sync with `src/backend/gpu/slots.rs`.
//
// CPU twin: the f64 slots of `jkrbem::backend::cpu::CpuBackend`.

const SLOTS: u32 = 64u;
const MAX_PARTIALS: u32 = 4096u;
// Under a CG guard: 1.0 once CG has converged (or failed) on the device, and the CG steps
// made since the guard began (f32 values, exact to 2^24).
const HALT_SLOT: u32 = 62u;
const STEPS_SLOT: u32 = 63u;
// "No slot": a kernel with an optional sum skips it.
const NO_SLOT: u32 = 0xffffffffu;

@group(0) @binding(8) var<storage, read_write> scalars: array<u32>;

var<workgroup> red: array<f32, WG>;
var<workgroup> red_count: u32;

// Pairwise sum of red[0..WG] into red[0]; every thread, uniform control flow.
fn red_tree(lid: u32) {
    for (var width = WG / 2u; width > 0u; width /= 2u) {
        if lid < width {
            red[lid] = red[lid] + red[lid + width];
        }
        workgroupBarrier();
    }
}

// The value of slot s, adding its partials if it is pending. Every thread of the workgroup
// must call it (uniform control flow); all get the same value.
fn slot_value(lid: u32, s: u32) -> f32 {
    if lid == 0u {
        red_count = scalars[SLOTS + s];
    }
    let count = workgroupUniformLoad(&red_count);
    if count == 0u {
        return bitcast<f32>(scalars[s]);
    }
    var sum = 0.0;
    let base = 2u * SLOTS + s * MAX_PARTIALS;
    for (var g = lid; g < count; g += WG) {
        sum += bitcast<f32>(scalars[base + g]);
    }
    red[lid] = sum;
    workgroupBarrier();
    red_tree(lid);
    let v = red[0];
    workgroupBarrier();
    return v;
}

// slots[num] / slots[den], 0 when the denominator is 0 (so the first CG direction is s = z).
fn slot_ratio(lid: u32, num: u32, den: u32) -> f32 {
    let n = slot_value(lid, num);
    let d = slot_value(lid, den);
    return select(n / d, 0.0, d == 0.0);
}

// This workgroup's contribution `v` (one per thread) to the pending sum of slot s, written as
// partial `group` of `groups`. Every thread, uniform control flow.
fn slot_partial(lid: u32, s: u32, v: f32, group: u32, groups: u32) {
    red[lid] = v;
    workgroupBarrier();
    red_tree(lid);
    if lid == 0u {
        scalars[2u * SLOTS + s * MAX_PARTIALS + group] = bitcast<u32>(red[0]);
        if group == 0u {
            scalars[SLOTS + s] = groups;
        }
    }
    workgroupBarrier();
}

// Whether a guarded CG batch has stopped (every thread gets the same answer; uniform control
// flow). Guarded kernels return at once when it has: their dispatches cost only a launch.
fn cg_halted(lid: u32) -> bool {
    if lid == 0u {
        red_count = scalars[HALT_SLOT];
    }
    return bitcast<f32>(workgroupUniformLoad(&red_count)) != 0.0;
}

// Whether v is an infinity or a NaN (from its bits, which no fast-math can assume away).
fn non_finite(v: f32) -> bool {
    return (bitcast<u32>(v) & 0x7f800000u) == 0x7f800000u;
}

// Set slot s to a final value (from one thread).
fn slot_set(s: u32, v: f32) {
    scalars[s] = bitcast<u32>(v);
    scalars[SLOTS + s] = 0u;
}
