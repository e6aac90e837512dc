// Reductions over the contact set C (mask = 1) read by the host once per state, f32: the
// total pressure with the contact count, and the first-crossing fraction of a load step.
//
// Two passes: each of G workgroups reduces a strided share of the elements (every thread
// keeps a compensated (Kahan) running sum, then the workgroup adds its 256 sums as a
// pairwise tree) into partials[g]; one workgroup then combines the G partials into a slot
// (shared/slots.wgsl). The rounding error grows like log2(n) instead of n.
// CPU twin: the f64 sums of `jkrbem::backend::cpu::CpuBackend` (sum_and_count,
// first_crossing).

// Must stay in sync with `ReduceParams` in src/backend/gpu/backend.rs.
struct Params {
    // Elements nx·ny.
    n: u32,
    // Number of partials G (workgroups of the first pass).
    groups: u32,
    // Destination slot of the finishing pass.
    out: u32,
    pad0: u32,
    // Detachment stress σ_c (first-crossing pass).
    sigma: f32,
    pad1: u32,
    pad2: u32,
    pad3: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> a: array<f32>;
@group(0) @binding(2) var<storage, read> b: array<f32>;
@group(0) @binding(3) var<storage, read> mask: array<u32>;
@group(0) @binding(4) var<storage, read_write> partials: array<f32>;
// Per-workgroup element counts; cell `groups` receives the total.
@group(0) @binding(5) var<storage, read_write> counts: array<u32>;

var<workgroup> tree_count: array<u32, WG>;

// Pairwise sum of red[0..WG] and tree_count[0..WG] into their first cells.
fn tree_sum_count(lid: u32) {
    for (var width = WG / 2u; width > 0u; width /= 2u) {
        if lid < width {
            red[lid] = red[lid] + red[lid + width];
            tree_count[lid] = tree_count[lid] + tree_count[lid + width];
        }
        workgroupBarrier();
    }
}

fn tree_min(lid: u32) {
    for (var width = WG / 2u; width > 0u; width /= 2u) {
        if lid < width {
            red[lid] = min(red[lid], red[lid + width]);
        }
        workgroupBarrier();
    }
}

// Σ_C a and |C| over this workgroup's share, into partials[g] and counts[g].
@compute @workgroup_size(WG)
fn sum_partials(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>) {
    var sum = 0.0;
    var carry = 0.0;
    var count = 0u;
    let step = params.groups * WG;
    for (var i = wid.x * WG + lid; i < params.n; i += step) {
        if mask[i] != 0u {
            let v = a[i] - carry;
            let t = sum + v;
            carry = (t - sum) - v;
            sum = t;
            count += 1u;
        }
    }
    red[lid] = sum;
    tree_count[lid] = count;
    workgroupBarrier();
    tree_sum_count(lid);
    if lid == 0u {
        partials[wid.x] = red[0];
        counts[wid.x] = tree_count[0];
    }
}

// min over C of (−σ − a)/(b − a) where b < −σ and b < a (clamped to [0, 1]); 1 if none.
@compute @workgroup_size(WG)
fn crossing_partials(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>) {
    var t = 1.0;
    let step = params.groups * WG;
    let s = params.sigma;
    for (var i = wid.x * WG + lid; i < params.n; i += step) {
        let pa = a[i];
        let pb = b[i];
        if mask[i] != 0u && pb < -s && pb < pa {
            t = min(t, clamp((-s - pa) / (pb - pa), 0.0, 1.0));
        }
    }
    red[lid] = t;
    workgroupBarrier();
    tree_min(lid);
    if lid == 0u {
        partials[wid.x] = red[0];
    }
}

// slot out = Σ partials, counts[groups] = Σ counts (one workgroup).
@compute @workgroup_size(WG)
fn finish_sum(@builtin(local_invocation_index) lid: u32) {
    var sum = 0.0;
    var count = 0u;
    for (var g = lid; g < params.groups; g += WG) {
        sum += partials[g];
        count += counts[g];
    }
    red[lid] = sum;
    tree_count[lid] = count;
    workgroupBarrier();
    tree_sum_count(lid);
    if lid == 0u {
        slot_set(params.out, red[0]);
        counts[params.groups] = tree_count[0];
    }
}

// slot out = min partials (one workgroup).
@compute @workgroup_size(WG)
fn finish_min(@builtin(local_invocation_index) lid: u32) {
    var t = 1.0;
    for (var g = lid; g < params.groups; g += WG) {
        t = min(t, partials[g]);
    }
    red[lid] = t;
    workgroupBarrier();
    tree_min(lid);
    if lid == 0u {
        slot_set(params.out, red[0]);
    }
}
