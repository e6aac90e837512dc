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
// start). `seed` and `mark` run over the whole grid and return at once for the elements
// outside their part. `mark` also lists each 16 × 16 tile that a generation's reach touches,
// once (the list only grows in a call, as the hole does), and `tiles` turns the list's length
// into the indirect dispatch of `jacobi` and `certify`: one workgroup a listed tile, none for a
// halted generation. A listed tile with no element of H (of the candidates) returns at once;
// the others stencil from workgroup memory (the tile of v with its halo, and G's table).
//
// Several generations are recorded before the host reads their counts (one slot each): a
// generation whose `guard` slot (the generation before it in the batch) counted nothing does
// nothing, so that the batch ends where the host's loop of one generation a read would.

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
    // The slot of `certified` this generation counts into, and the slot of the generation
    // before it in the batch (NO_GUARD: none; this generation then runs).
    slot: u32,
    guard: u32,
    // Tiles along x (the grid's tiles are numbered row by row).
    tiles_x: u32,
    _pad: u32,
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
// Elements certified by each generation of a batch (one slot each, BATCH of them; cleared by
// the host before the batch), then the count of the tiles listed (at LISTED) and their list
// (from LIST; both cleared by the host before the call).
@group(0) @binding(9) var<storage, read_write> certified: array<atomic<u32>>;
// Whether each tile is listed (cleared by the host before the call).
@group(0) @binding(10) var<storage, read_write> tile_listed: array<atomic<u32>>;
// The indirect dispatch of `jacobi` and `certify` (workgroups along x, y, z).
@group(0) @binding(11) var<storage, read_write> dispatch: array<u32>;

const HOLE: u32 = 1u;
const CANDIDATE: u32 = 2u;
const NO_GUARD: u32 = 0xffffffffu;
// The layout of `certified` (`MAX_GENERATION_BATCH` in src/backend/gpu/backend.rs).
const BATCH: u32 = 16u;
const LISTED: u32 = BATCH;
const LIST: u32 = BATCH + 1u;
// Workgroups along x of an indirect dispatch at most (the per-dimension limit).
const ROW: u32 = 65535u;
// The tiles of `jacobi` and `certify`: TILE × TILE elements (one thread each, WG in all),
// with a halo of HALO elements, the largest truncation they hold.
const TILE: u32 = 16u;
const HALO: u32 = 12u;
const SPAN: u32 = 40u; // TILE + 2 HALO
const G_SIDE: u32 = 25u; // 2 HALO + 1

var<workgroup> v_tile: array<f32, 1600>; // SPAN²
var<workgroup> g_tile: array<f32, 625>; // G_SIDE²
var<workgroup> busy: atomic<u32>;
var<workgroup> go: u32;

// Whether the generation before this one in the batch certified nothing (this one then does
// nothing).
fn halted() -> bool {
    return params.guard != NO_GUARD && atomicLoad(&certified[params.guard]) == 0u;
}

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
    if halted() || i >= params.nx * params.ny || gen[i] != params.generation {
        return;
    }
    let reach = i32(max(params.hole_reach, params.candidate_reach));
    let x = i32(i % params.nx);
    let y = i32(i / params.nx);
    // The tiles this element's reach touches, each listed once.
    let lo = vec2<u32>(u32(max(x - reach, 0)), u32(max(y - reach, 0))) / TILE;
    let hi = vec2<u32>(
        u32(min(x + reach, i32(params.nx) - 1)),
        u32(min(y + reach, i32(params.ny) - 1)),
    ) / TILE;
    for (var ty = lo.y; ty <= hi.y; ty++) {
        for (var tx = lo.x; tx <= hi.x; tx++) {
            let t = ty * params.tiles_x + tx;
            if atomicExchange(&tile_listed[t], 1u) == 0u {
                let k = atomicAdd(&certified[LISTED], 1u);
                atomicStore(&certified[LIST + k], t);
            }
        }
    }
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

// Whether any thread of the workgroup has work (`mine`); every thread calls it, in uniform
// control flow.
fn any_in_workgroup(mine: bool, lid: u32) -> bool {
    if lid == 0u {
        atomicStore(&busy, 0u);
    }
    workgroupBarrier();
    if mine {
        atomicStore(&busy, 1u);
    }
    workgroupBarrier();
    if lid == 0u {
        go = atomicLoad(&busy);
    }
    return workgroupUniformLoad(&go) != 0u;
}

// The tile's v (its elements and a halo of HALO, zero off the grid) and G's table into
// workgroup memory; every thread calls it, in uniform control flow.
fn load_tile(origin: vec2<i32>, lid: u32) {
    for (var k = lid; k < SPAN * SPAN; k += WG) {
        let xx = origin.x - i32(HALO) + i32(k % SPAN);
        let yy = origin.y - i32(HALO) + i32(k / SPAN);
        var v = 0.0;
        if xx >= 0 && yy >= 0 && xx < i32(params.nx) && yy < i32(params.ny) {
            v = v_in[u32(yy) * params.nx + u32(xx)];
        }
        v_tile[k] = v;
    }
    let side = 2u * params.truncation + 1u;
    for (var k = lid; k < side * side; k += WG) {
        g_tile[k] = g[k];
    }
    workgroupBarrier();
}

// Σ_{o ≠ 0} g(o) v_in[i + o] over the offsets within the truncation (at most HALO), on the
// grid, for the element (x, y) of the tile at `origin`, from workgroup memory (v_in is zero
// outside the hole; the table's centre is zero). Each stencil row is summed apart and then
// added to the total, as the host twin does, so that no chain of roundings is longer than
// two stencil sides (what the safety factor on Δ is sized for).
fn g_times_v(x: i32, y: i32, origin: vec2<i32>) -> f32 {
    let t = i32(params.truncation);
    let side = 2 * t + 1;
    var acc = 0.0;
    for (var yy = max(y - t, 0); yy <= min(y + t, i32(params.ny) - 1); yy++) {
        var row = 0.0;
        let g_row = (yy - y + t) * side - x + t;
        let v_row = (yy - origin.y + i32(HALO)) * i32(SPAN) - origin.x + i32(HALO);
        for (var xx = max(x - t, 0); xx <= min(x + t, i32(params.nx) - 1); xx++) {
            row += g_tile[g_row + xx] * v_tile[v_row + xx];
        }
        acc += row;
    }
    return acc;
}

// The indirect dispatch of this generation's `jacobi` and `certify`: one workgroup a listed
// tile (rows of ROW), none where the generation is halted.
@compute @workgroup_size(1)
fn tiles() {
    let n = select(atomicLoad(&certified[LISTED]), 0u, halted());
    dispatch[0] = min(n, ROW);
    dispatch[1] = (n + ROW - 1u) / ROW;
    dispatch[2] = 1u;
}

// The origin (element x, y) of the listed tile a workgroup of an indirect dispatch takes, and
// whether there is one (the last row of workgroups may run past the list).
fn listed_tile(wid: vec3<u32>) -> vec3<i32> {
    let k = wid.y * ROW + wid.x;
    if k >= atomicLoad(&certified[LISTED]) {
        return vec3<i32>(0, 0, 0);
    }
    let t = atomicLoad(&certified[LIST + k]);
    return vec3<i32>(i32((t % params.tiles_x) * TILE), i32((t / params.tiles_x) * TILE), 1);
}

// A thread of a listed tile: the tile's origin, its element (x, y) and index i, and whether
// it has an element to work on (a listed tile, inside the grid, the generation not halted).
struct TileThread {
    origin: vec2<i32>,
    x: i32,
    y: i32,
    i: u32,
    live: bool,
}

fn tile_thread(wid: vec3<u32>, lid3: vec3<u32>) -> TileThread {
    let tile = listed_tile(wid);
    let x = tile.x + i32(lid3.x);
    let y = tile.y + i32(lid3.y);
    let live = tile.z != 0 && x < i32(params.nx) && y < i32(params.ny) && !halted();
    return TileThread(tile.xy, x, y, u32(y) * params.nx + u32(x), live);
}

// Whether any thread of the workgroup has work (`mine`), and if so the tile at `origin`
// loaded into workgroup memory; every thread calls it, in uniform control flow.
fn tile_loaded(mine: bool, origin: vec2<i32>, lid: u32) -> bool {
    if !any_in_workgroup(mine, lid) {
        return false;
    }
    load_tile(origin, lid);
    return true;
}

@compute @workgroup_size(16, 16)
fn jacobi(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(local_invocation_id) lid3: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let t = tile_thread(wid, lid3);
    let i = t.i;
    var mine = false;
    if t.live {
        mine = atomicLoad(&role[i]) == HOLE;
    }
    if !tile_loaded(mine, t.origin, lid) {
        return;
    }
    if mine {
        let b = select(0.0, -before[i], gen[i] != 0u);
        v_out[i] = b - g_times_v(t.x, t.y, t.origin);
    }
}

@compute @workgroup_size(16, 16)
fn certify(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(local_invocation_id) lid3: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let t = tile_thread(wid, lid3);
    let i = t.i;
    var mine = false;
    if t.live {
        mine = atomicLoad(&role[i]) == CANDIDATE && mask[i] != 0u;
    }
    if !tile_loaded(mine, t.origin, lid) {
        return;
    }
    if !mine {
        return;
    }
    let delta = min(g_times_v(t.x, t.y, t.origin), 0.0);
    if before[i] < 0.0 && before[i] + params.safety * delta < params.limit {
        mask[i] = 0u;
        p[i] = 0.0;
        gen[i] = params.generation + 1u;
        atomicAdd(&certified[params.slot], 1u);
    } else {
        // The round's predicted start; the last generation's (which certifies none) stays.
        p[i] = before[i] + delta;
    }
}
