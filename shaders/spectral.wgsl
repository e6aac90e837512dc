// The real-to-complex / complex-to-real layer of the 2-D spectral filter
// dst = crop(IFFT(symbol · FFT(pad(src)))), around the complex FFTs of fft.wgsl.
//
// A real row of mx values (the nx data values, zero-padded) is packed as hx = mx/2 complex
// values z[k] = x[2k] + i x[2k+1] and transformed with a half-size complex FFT; `split_rows`
// turns Z into the row's half spectrum X[k], k in [0, hx], and writes it transposed
// (column-major, hx + 1 columns of my values) with the padding rows ny..my set to zero, so
// the column FFTs run on contiguous lines. After the column FFTs, the multiply and the
// inverse column FFTs, `merge_cols` reads back only the ny rows that are kept (the crop),
// undoes the split and transposes to rows again; `unpack_rows` keeps the first nx values.
// The normalisation 1/(hx·my) is folded into the symbol on the host.
//
// CPU twin: `jkrbem::backend::cpu::spectral::SpectralFilter` (realfft/rustfft in f64).

// Must stay in sync with `SpectralParams` in src/backend/gpu/spectral.rs.
struct Params {
    // Data shape nx × ny (real values, row-major).
    nx: u32,
    ny: u32,
    // Transform size mx × my (mx = 2·hx).
    mx: u32,
    my: u32,
    // Half row length hx = mx / 2 (complex values per packed row).
    hx: u32,
    // 1: multiply the input (pack_rows) or the output (unpack_rows) by the contact mask.
    masked: u32,
    pad0: u32,
    pad1: u32,
}

const WG: u32 = 256u;

@group(0) @binding(0) var<uniform> params: Params;
// Real field nx × ny (input of pack_rows).
@group(0) @binding(1) var<storage, read> src: array<f32>;
// Real field nx × ny (output of unpack_rows).
@group(0) @binding(2) var<storage, read_write> dst: array<f32>;
// Packed rows: ny rows of hx complex values.
@group(0) @binding(3) var<storage, read_write> rows: array<vec2<f32>>;
// Column spectra: hx + 1 columns of my complex values.
@group(0) @binding(4) var<storage, read_write> cols: array<vec2<f32>>;
// e^{-2πik/mx}, k in [0, hx], computed on the host in f64.
@group(0) @binding(5) var<storage, read> twiddle: array<vec2<f32>>;
// Real symbol, hx + 1 columns of my values, already scaled by 1/(hx·my).
@group(0) @binding(6) var<storage, read> symbol: array<f32>;
// Contact mask, nx × ny (1 = in contact).
@group(0) @binding(7) var<storage, read> mask: array<u32>;

fn index(gid: vec3<u32>, nwg: vec3<u32>) -> u32 {
    return gid.x + gid.y * nwg.x * WG;
}

fn cmul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

fn conj(a: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x, -a.y);
}

// The value x[i] of row j, zero beyond the data (padding), masked if asked.
fn input(i: u32, j: u32) -> f32 {
    if i >= params.nx {
        return 0.0;
    }
    let at = j * params.nx + i;
    let v = src[at];
    if params.masked != 0u && mask[at] == 0u {
        return 0.0;
    }
    return v;
}

@compute @workgroup_size(WG)
fn pack_rows(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>) {
    let idx = index(gid, nwg);
    if idx >= params.ny * params.hx {
        return;
    }
    let j = idx / params.hx;
    let k = idx % params.hx;
    rows[idx] = vec2<f32>(input(2u * k, j), input(2u * k + 1u, j));
}

// X[k] = E[k] + e^{-2πik/mx}·O[k], E = (Z[k] + conj Z[hx−k])/2, O = (Z[k] − conj Z[hx−k])/(2i).
@compute @workgroup_size(WG)
fn split_rows(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>) {
    let idx = index(gid, nwg);
    let hx = params.hx;
    if idx >= (hx + 1u) * params.my {
        return;
    }
    let k = idx / params.my;
    let j = idx % params.my;
    if j >= params.ny {
        cols[idx] = vec2<f32>(0.0, 0.0);
        return;
    }
    let zk = rows[j * hx + k % hx];
    let zc = conj(rows[j * hx + (hx - k) % hx]);
    let e = 0.5 * (zk + zc);
    let diff = 0.5 * (zk - zc);
    let o = vec2<f32>(diff.y, -diff.x);
    cols[idx] = e + cmul(twiddle[k], o);
}

@compute @workgroup_size(WG)
fn multiply_symbol(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>) {
    let idx = index(gid, nwg);
    if idx >= (params.hx + 1u) * params.my {
        return;
    }
    cols[idx] = cols[idx] * symbol[idx];
}

// Z[k] = E[k] + i·O[k], E = (X[k] + conj X[hx−k])/2, O = (X[k] − conj X[hx−k])·e^{+2πik/mx}/2,
// for the kept rows j < ny only.
@compute @workgroup_size(WG)
fn merge_cols(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>) {
    let idx = index(gid, nwg);
    let hx = params.hx;
    if idx >= params.ny * hx {
        return;
    }
    let j = idx / hx;
    let k = idx % hx;
    let my = params.my;
    let xk = cols[k * my + j];
    let xc = conj(cols[(hx - k) * my + j]);
    let e = 0.5 * (xk + xc);
    let o = cmul(0.5 * (xk - xc), conj(twiddle[k]));
    rows[idx] = e + vec2<f32>(-o.y, o.x);
}

@compute @workgroup_size(WG)
fn unpack_rows(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>) {
    let idx = index(gid, nwg);
    if idx >= params.nx * params.ny {
        return;
    }
    let j = idx / params.nx;
    let i = idx % params.nx;
    let z = rows[j * params.hx + i / 2u];
    var v = select(z.y, z.x, i % 2u == 0u);
    if params.masked != 0u && mask[idx] == 0u {
        v = 0.0;
    }
    dst[idx] = v;
}
