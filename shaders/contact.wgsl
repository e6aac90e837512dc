// One sweep of the Pohrt–Popov rule on the contact set (mask = 1), f32:
// detach elements of C with p < −σ_c, attach elements off C whose gap g = h − d + u < 0
// (unless the sweep only detaches), then p = 0 off C; count detached, attached, |C| and the elements of C on the domain's
// outer ring (workgroup atomics, then one global atomic per workgroup and counter).
// The rule for one element is `backend::rules::sweep_element`; CPU twin: `CpuBackend::update_contact`.

// Must stay in sync with `ContactParams` in src/backend/gpu/backend.rs.
struct Params {
    nx: u32,
    ny: u32,
    // Approach d (length).
    d: f32,
    // Detachment stress σ_c (stress; 0 for the non-adhesive rule).
    sigma: f32,
    // 1: attach elements off C whose gap is negative; 0: detach only (u is not read).
    attach: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read_write> p: array<f32>;
@group(0) @binding(2) var<storage, read> u: array<f32>;
@group(0) @binding(3) var<storage, read_write> mask: array<u32>;
@group(0) @binding(4) var<storage, read> profile: array<f32>;
// detached, attached, |C|, |C ∩ outer ring|; cleared by the host before the sweep.
@group(0) @binding(5) var<storage, read_write> counters: array<atomic<u32>, 4>;

var<workgroup> local: array<atomic<u32>, 4>;

@compute @workgroup_size(WG)
fn update_contact(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    if lid < 4u {
        atomicStore(&local[lid], 0u);
    }
    workgroupBarrier();
    let i = gid.x + gid.y * nwg.x * WG;
    if i < params.nx * params.ny {
        var m = mask[i] != 0u;
        let attach = params.attach != 0u && profile[i] - params.d + u[i] < 0.0;
        let flip = select(attach, p[i] < -params.sigma, m);
        if flip {
            atomicAdd(&local[select(1u, 0u, m)], 1u);
            m = !m;
            mask[i] = select(0u, 1u, m);
        }
        if m {
            atomicAdd(&local[2], 1u);
            let x = i % params.nx;
            let y = i / params.nx;
            if x == 0u || y == 0u || x == params.nx - 1u || y == params.ny - 1u {
                atomicAdd(&local[3], 1u);
            }
        } else {
            p[i] = 0.0;
        }
    }
    workgroupBarrier();
    if lid < 4u {
        let v = atomicLoad(&local[lid]);
        if v > 0u {
            atomicAdd(&counters[lid], v);
        }
    }
}
