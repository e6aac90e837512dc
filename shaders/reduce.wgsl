// Reductions over the contact set C (mask = 1) into device slots, f32.
//
// Two passes: each of G workgroups reduces a strided share of the elements (every thread
// keeps a compensated (Kahan) running sum, then the workgroup adds its 256 sums as a
// pairwise tree) into partials[g]; one workgroup then adds the G partials as a pairwise
// tree into slots[out]. The rounding error grows like log2(n) instead of n.
// CPU twin: the f64 sums of `jkrbem::backend::cpu::CpuBackend` (dot, sum_and_count,
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

const WG: u32 = 256u;

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> a: array<f32>;
@group(0) @binding(2) var<storage, read> b: array<f32>;
@group(0) @binding(3) var<storage, read> mask: array<u32>;
@group(0) @binding(4) var<storage, read_write> partials: array<f32>;
// Per-workgroup element counts; cell `groups` receives the total.
@group(0) @binding(5) var<storage, read_write> counts: array<u32>;
@group(0) @binding(6) var<storage, read_write> slots: array<f32>;

var<workgroup> tree: array<f32, WG>;
var<workgroup> tree_count: array<u32, WG>;

// Pairwise sum of tree[0..WG] into tree[0].
fn tree_sum(lid: u32) {
    for (var width = WG / 2u; width > 0u; width /= 2u) {
        if lid < width {
            tree[lid] = tree[lid] + tree[lid + width];
            tree_count[lid] = tree_count[lid] + tree_count[lid + width];
        }
        workgroupBarrier();
    }
}

fn tree_min(lid: u32) {
    for (var width = WG / 2u; width > 0u; width /= 2u) {
        if lid < width {
            tree[lid] = min(tree[lid], tree[lid + width]);
        }
        workgroupBarrier();
    }
}

// Compensated sum of the masked a·b (`product`) or a (`!product`) over this thread's share.
fn share_sum(lid: u32, g: u32, product: bool) {
    var sum = 0.0;
    var carry = 0.0;
    var count = 0u;
    let step = params.groups * WG;
    for (var i = g * WG + lid; i < params.n; i += step) {
        if mask[i] != 0u {
            var v = a[i];
            if product {
                v = v * b[i];
            }
            let yv = v - carry;
            let t = sum + yv;
            carry = (t - sum) - yv;
            sum = t;
            count += 1u;
        }
    }
    tree[lid] = sum;
    tree_count[lid] = count;
    workgroupBarrier();
}

@compute @workgroup_size(WG)
fn dot_partials(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>) {
    share_sum(lid, wid.x, true);
    tree_sum(lid);
    if lid == 0u {
        partials[wid.x] = tree[0];
        counts[wid.x] = tree_count[0];
    }
}

@compute @workgroup_size(WG)
fn sum_partials(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>) {
    share_sum(lid, wid.x, false);
    tree_sum(lid);
    if lid == 0u {
        partials[wid.x] = tree[0];
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
    tree[lid] = t;
    workgroupBarrier();
    tree_min(lid);
    if lid == 0u {
        partials[wid.x] = tree[0];
    }
}

// slots[out] = Σ partials, counts[groups] = Σ counts (one workgroup).
@compute @workgroup_size(WG)
fn finish_sum(@builtin(local_invocation_index) lid: u32) {
    var sum = 0.0;
    var count = 0u;
    for (var g = lid; g < params.groups; g += WG) {
        sum += partials[g];
        count += counts[g];
    }
    tree[lid] = sum;
    tree_count[lid] = count;
    workgroupBarrier();
    tree_sum(lid);
    if lid == 0u {
        slots[params.out] = tree[0];
        counts[params.groups] = tree_count[0];
    }
}

// slots[out] = min partials (one workgroup).
@compute @workgroup_size(WG)
fn finish_min(@builtin(local_invocation_index) lid: u32) {
    var t = 1.0;
    for (var g = lid; g < params.groups; g += WG) {
        t = min(t, partials[g]);
    }
    tree[lid] = t;
    workgroupBarrier();
    tree_min(lid);
    if lid == 0u {
        slots[params.out] = tree[0];
    }
}
