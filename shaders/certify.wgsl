// Detachments certain before a solve (f32), generation by generation: the device's side of
// `backend::certify` (whose module notes give the bound and why it holds). CPU twin:
// `backend::certify::certify_detached`, which takes the same steps on the hole's elements only.
//
// Per call: `seed` once (gen = 1 on the elements the sweep just detached: off C with p ≠ 0
// before it; gen, role and both v buffers cleared by the host first). Per generation g:
// `mark` (the hole H: elements off C within the hole's reach of an element of generation g;
// the candidates: elements of C within the candidates' reach of one; scattered from the
// generation's elements), `jacobi` JACOBI_STEPS times (ping-pong between v_in and v_out),
// then `certify` (an element of C whose bound is below the limit leaves C, p = 0 on it,
// gen = g + 1, counted; on a candidate kept p is set to before + Δ, the round's predicted
// start). Every kernel runs over the whole grid and returns at once for the elements outside
// its part (the generation's elements, H, the candidates), so a generation costs the hole's
// work plus a few reads per element.

// Must stay in sync with `CertifyParams` in src/backend/gpu/backend.rs.
struct Params {
    nx: u32,
    ny: u32,
    // The generation g being taken (from 1).
    generation: u32,
    // G's truncation T (elements); the table `g` is (2T + 1)², row-major, G off the
    // diagonal (centre 0: `backend::certify::off_diagonal`).
    truncation: u32,
    // Reach (elements, along x and y) of the hole and of the candidates.
    hole_reach: u32,
    candidate_reach: u32,
    // −σ_c − 3ε (stress): an element is certified when p + safety·Δ lies below it.
    limit: f32,
    // The disc's safety factor on Δ (dimensionless).
    safety: f32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read_write> p: array<f32>;
@group(0) @binding(2) var<storage, read> before: array<f32>;
@group(0) @binding(3) var<storage, read_write> mask: array<u32>;
// Generation each element was removed in (0: never).
@group(0) @binding(4) var<storage, read_write> gen: array<u32>;
// 0: neither; 1: in the hole; 2: a candidate (atomic: `mark` scatters it).
@group(0) @binding(5) var<storage, read_write> role: array<atomic<u32>>;
@group(0) @binding(6) var<storage, read> v_in: array<f32>;
@group(0) @binding(7) var<storage, read_write> v_out: array<f32>;
@group(0) @binding(8) var<storage, read> g: array<f32>;
// Elements certified by this dispatch; cleared by the host before it.
@group(0) @binding(9) var<storage, read_write> certified: array<atomic<u32>, 1>;

const HOLE: u32 = 1u;
const CANDIDATE: u32 = 2u;

fn element(gid: vec3<u32>, nwg: vec3<u32>) -> u32 {
    return gid.x + gid.y * nwg.x * WG;
}

@compute @workgroup_size(WG)
fn seed(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    let i = element(gid, nwg);
    if i >= params.nx * params.ny {
        return;
    }
    if mask[i] == 0u && before[i] != 0.0 {
        gen[i] = 1u;
    }
}

// Scattered from the elements of generation g (as the CPU twin grows its hole): every
// element within the reaches of one takes its role, so that a generation costs its own
// elements' stencils plus one read per element. Writers of an element store the same role
// (it depends only on whether that element is in C, which `mark` does not change).
@compute @workgroup_size(WG)
fn mark(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    let i = element(gid, nwg);
    if i >= params.nx * params.ny || gen[i] != params.generation {
        return;
    }
    let reach = i32(max(params.hole_reach, params.candidate_reach));
    let x = i32(i % params.nx);
    let y = i32(i / params.nx);
    for (var yy = max(y - reach, 0); yy <= min(y + reach, i32(params.ny) - 1); yy++) {
        for (var xx = max(x - reach, 0); xx <= min(x + reach, i32(params.nx) - 1); xx++) {
            let j = u32(yy) * params.nx + u32(xx);
            let dist = u32(max(abs(xx - x), abs(yy - y)));
            if mask[j] != 0u {
                // A candidate stays one while in C.
                if dist <= params.candidate_reach {
                    atomicStore(&role[j], CANDIDATE);
                }
            } else if dist <= params.hole_reach {
                // The hole only grows (a candidate certified before joins it).
                atomicStore(&role[j], HOLE);
            }
        }
    }
}

// Σ_{o ≠ 0} g(o) v_in[i + o] over the offsets within the truncation, on the grid (v_in is
// zero outside the hole; the table's centre is zero). Each stencil row is summed apart and
// then added to the total, as the host twin does, so that no chain of roundings is longer
// than two stencil sides (what the safety factor on Δ is sized for).
fn g_times_v(i: u32) -> f32 {
    let t = i32(params.truncation);
    let side = 2 * t + 1;
    let x = i32(i % params.nx);
    let y = i32(i / params.nx);
    var acc = 0.0;
    for (var yy = max(y - t, 0); yy <= min(y + t, i32(params.ny) - 1); yy++) {
        var row = 0.0;
        for (var xx = max(x - t, 0); xx <= min(x + t, i32(params.nx) - 1); xx++) {
            let j = u32(yy) * params.nx + u32(xx);
            row += g[(yy - y + t) * side + xx - x + t] * v_in[j];
        }
        acc += row;
    }
    return acc;
}

@compute @workgroup_size(WG)
fn jacobi(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    let i = element(gid, nwg);
    if i >= params.nx * params.ny || atomicLoad(&role[i]) != HOLE {
        return;
    }
    let b = select(0.0, -before[i], gen[i] != 0u);
    v_out[i] = b - g_times_v(i);
}

@compute @workgroup_size(WG)
fn certify(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    let i = element(gid, nwg);
    if i >= params.nx * params.ny || atomicLoad(&role[i]) != CANDIDATE || mask[i] == 0u {
        return;
    }
    let delta = min(g_times_v(i), 0.0);
    if before[i] < 0.0 && before[i] + params.safety * delta < params.limit {
        mask[i] = 0u;
        p[i] = 0.0;
        gen[i] = params.generation + 1u;
        atomicAdd(&certified[0], 1u);
    } else {
        // The round's predicted start; the last generation's (which certifies none) stays.
        p[i] = before[i] + delta;
    }
}
