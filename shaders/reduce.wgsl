// Reductions over the contact set C (mask = 1) read by the host once per state, f32: the
// state's measurement (total pressure, contact count, chords, index box), the
// first-crossing fraction of a load step, and the largest |value| of a field on C.
//
// Two passes: each of G workgroups reduces a strided share of the elements (every thread
// keeps a compensated (Kahan) running sum, then the workgroup adds its 256 sums as a
// pairwise tree) into partials[g]; one workgroup then combines the G partials into a slot
// (shared/slots.wgsl). The rounding error grows like log2(n) instead of n.
// CPU twins: `jkrbem::backend::measure::measure_mask`, `jkrbem::backend::rules::
// crossing_fraction` (the rule per element) and the f64 `max_abs` of
// `jkrbem::backend::cpu::CpuBackend`.

// Must stay in sync with `ReduceParams` in src/backend/gpu/backend.rs.
struct Params {
    // Elements nx·ny.
    n: u32,
    // Number of partials G (workgroups of the first pass).
    groups: u32,
    // Destination slot of the finishing pass.
    out: u32,
    // Elements along x (measurement).
    nx: u32,
    // Detachment stress σ_c (first-crossing pass).
    sigma: f32,
    // Elements along y (measurement).
    ny: u32,
    // The major chord's direction (cos θ, sin θ) in the grid's frame (measurement).
    cos: f32,
    sin: f32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> a: array<f32>;
@group(0) @binding(2) var<storage, read> b: array<f32>;
@group(0) @binding(3) var<storage, read> mask: array<u32>;
@group(0) @binding(4) var<storage, read_write> partials: array<f32>;
// Per-workgroup element counts; cell `groups` receives the total.
@group(0) @binding(5) var<storage, read_write> counts: array<u32>;

var<workgroup> tree_count: array<u32, WG>;
var<workgroup> tree_chords: array<vec2<f32>, WG>;
var<workgroup> tree_box: array<vec4<u32>, WG>;

// "No element": the start of a box bound's minimum.
const NONE: u32 = 0xffffffffu;

// The measurement's trees: pairwise sums of red, tree_count and tree_chords, minima of
// tree_box, into their first cells.
fn tree_measure(lid: u32) {
    for (var width = WG / 2u; width > 0u; width /= 2u) {
        if lid < width {
            red[lid] = red[lid] + red[lid + width];
            tree_count[lid] = tree_count[lid] + tree_count[lid + width];
            tree_chords[lid] = tree_chords[lid] + tree_chords[lid + width];
            tree_box[lid] = min(tree_box[lid], tree_box[lid + width]);
        }
        workgroupBarrier();
    }
}

// P(U·p + V·q ≤ s) for U, V uniform on [0, 1] and p ≥ q ≥ 0, p > 0 (the area of the unit
// square below a line); CPU twin `below` in src/backend/measure.rs.
fn below(s: f32, p: f32, q: f32) -> f32 {
    if q < 1e-4 {
        return clamp(s / p, 0.0, 1.0);
    }
    return clamp((ramp_integral(s, p) - ramp_integral(s - q, p)) / q, 0.0, 1.0);
}

// The antiderivative of clamp(s / p, 0, 1).
fn ramp_integral(s: f32, p: f32) -> f32 {
    if s <= 0.0 {
        return 0.0;
    }
    if s <= p {
        return s * s / (2.0 * p);
    }
    return s - p / 2.0;
}

// Area of the unit square with lower-left corner c within |n·(x, y)| < ½, for a unit normal n
// (all in elements); CPU twin `band_area`.
fn band_area(c: vec2<f32>, n: vec2<f32>) -> f32 {
    let low = dot(n, c) + min(n.x, 0.0) + min(n.y, 0.0);
    // The square's points lie within [low, low + |n.x| + |n.y|] of the line; ≤ √2 wide.
    if low > 0.5 || low < -2.0 {
        return 0.0;
    }
    let p = max(abs(n.x), abs(n.y));
    let q = min(abs(n.x), abs(n.y));
    return below(0.5 - low, p, q) - below(-0.5 - low, p, q);
}

fn tree_min(lid: u32) {
    for (var width = WG / 2u; width > 0u; width /= 2u) {
        if lid < width {
            red[lid] = min(red[lid], red[lid + width]);
        }
        workgroupBarrier();
    }
}

// The measurement of a state (CPU twin: `jkrbem::backend::measure::measure_mask`), over
// this workgroup's share: Σ_C a (compensated), |C|, the chords of C along the two axes through
// the grid centre (band areas of the contact squares, in elements) and C's index box.
// Partials: partials[g], partials[G + g], partials[2G + g] (sum, chord a, chord b);
// counts[g] (count) and counts[G + 4g .. G + 4g + 4] (i_min, !i_max, j_min, !j_max: every box
// bound a minimum, the maxima complemented).
@compute @workgroup_size(WG)
fn measure_partials(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>) {
    var sum = 0.0;
    var carry = 0.0;
    var count = 0u;
    var chords = vec2<f32>(0.0, 0.0);
    var box = vec4<u32>(NONE, NONE, NONE, NONE);
    let step = params.groups * WG;
    let half = vec2<f32>(f32(params.nx / 2u), f32(params.ny / 2u));
    for (var i = wid.x * WG + lid; i < params.n; i += step) {
        if mask[i] != 0u {
            let v = a[i] - carry;
            let t = sum + v;
            carry = (t - sum) - v;
            sum = t;
            count += 1u;
            let ij = vec2<u32>(i % params.nx, i / params.nx);
            let corner = vec2<f32>(ij) - half;
            chords += vec2<f32>(
                band_area(corner, vec2<f32>(-params.sin, params.cos)),
                band_area(corner, vec2<f32>(params.cos, params.sin)),
            );
            box = min(box, vec4<u32>(ij.x, ~ij.x, ij.y, ~ij.y));
        }
    }
    red[lid] = sum;
    tree_count[lid] = count;
    tree_chords[lid] = chords;
    tree_box[lid] = box;
    workgroupBarrier();
    tree_measure(lid);
    if lid == 0u {
        let g = params.groups;
        partials[wid.x] = red[0];
        partials[g + wid.x] = tree_chords[0].x;
        partials[2u * g + wid.x] = tree_chords[0].y;
        counts[wid.x] = tree_count[0];
        for (var c = 0u; c < 4u; c++) {
            counts[g + 4u * wid.x + c] = tree_box[0][c];
        }
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

// −max over C of |a| (0 if C is empty), as a minimum so that `finish_min` completes it.
@compute @workgroup_size(WG)
fn max_abs_partials(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>) {
    var t = 0.0;
    let step = params.groups * WG;
    for (var i = wid.x * WG + lid; i < params.n; i += step) {
        if mask[i] != 0u {
            t = min(t, -abs(a[i]));
        }
    }
    red[lid] = t;
    workgroupBarrier();
    tree_min(lid);
    if lid == 0u {
        partials[wid.x] = red[0];
    }
}

// The measurement from the partials (one workgroup): slot out = Σ_C a, and at
// counts[5G .. 5G + 8]: |C|, i_min, i_max, j_min, j_max, then the f32 bits of Σ_C a, chord a
// and chord b (one read brings all of it back).
@compute @workgroup_size(WG)
fn finish_measure(@builtin(local_invocation_index) lid: u32) {
    let g = params.groups;
    var sum = 0.0;
    var count = 0u;
    var chords = vec2<f32>(0.0, 0.0);
    var box = vec4<u32>(NONE, NONE, NONE, NONE);
    for (var k = lid; k < g; k += WG) {
        sum += partials[k];
        count += counts[k];
        chords += vec2<f32>(partials[g + k], partials[2u * g + k]);
        let b = 4u * k + g;
        box = min(box, vec4<u32>(counts[b], counts[b + 1u], counts[b + 2u], counts[b + 3u]));
    }
    red[lid] = sum;
    tree_count[lid] = count;
    tree_chords[lid] = chords;
    tree_box[lid] = box;
    workgroupBarrier();
    tree_measure(lid);
    if lid == 0u {
        slot_set(params.out, red[0]);
        let o = 5u * g;
        counts[o] = tree_count[0];
        counts[o + 1u] = tree_box[0].x;
        counts[o + 2u] = ~tree_box[0].y;
        counts[o + 3u] = tree_box[0].z;
        counts[o + 4u] = ~tree_box[0].w;
        counts[o + 5u] = bitcast<u32>(red[0]);
        counts[o + 6u] = bitcast<u32>(tree_chords[0].x);
        counts[o + 7u] = bitcast<u32>(tree_chords[0].y);
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
