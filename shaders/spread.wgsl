// A cascade round's predicted start (f32): every element i of C (mask = 1) takes
// p[i] += Σ_o w_o · before[i + o] over the offsets o within the share radius whose element lies
// on the grid and off C. `before` is p as it was before the sweep (zero off the contact set it
// was on), so only the elements the sweep just detached hand on their load. The shares w are
// `backend::shares::detachment_shares`; CPU twin: `backend::shares::spread_detached`.

// Must stay in sync with `SpreadParams` in src/backend/gpu/backend.rs.
struct Params {
    nx: u32,
    ny: u32,
    // Elements either side that take a share (R); the shares are (2R + 1)², row-major.
    radius: u32,
    _pad0: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read_write> p: array<f32>;
@group(0) @binding(2) var<storage, read> before: array<f32>;
@group(0) @binding(3) var<storage, read> mask: array<u32>;
@group(0) @binding(4) var<storage, read> shares: array<f32>;

@compute @workgroup_size(WG)
fn spread_detached(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    let i = gid.x + gid.y * nwg.x * WG;
    if i >= params.nx * params.ny || mask[i] == 0u {
        return;
    }
    let x = i32(i % params.nx);
    let y = i32(i / params.nx);
    let r = i32(params.radius);
    let side = 2 * r + 1;
    var acc = 0.0;
    for (var oy = -r; oy <= r; oy++) {
        let yy = y + oy;
        if yy < 0 || yy >= i32(params.ny) {
            continue;
        }
        for (var ox = -r; ox <= r; ox++) {
            let xx = x + ox;
            if xx < 0 || xx >= i32(params.nx) {
                continue;
            }
            let j = u32(yy) * params.nx + u32(xx);
            if mask[j] == 0u {
                acc += shares[(oy + r) * side + ox + r] * before[j];
            }
        }
    }
    p[i] += acc;
}
