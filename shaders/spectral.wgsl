// The 2-D real spectral filter dst = crop(IFFT(symbol · FFT(pad(src)))) in three passes, each
// one dispatch with its FFTs in workgroup memory (shared/fft.wgsl):
//
// 1. `rows_forward`: each of the ny data rows (mx real values: the nx data values, then zeros
//    when padded) is packed as L = mx/2 complex values z[k] = x[2k] + i·x[2k+1], transformed,
//    and split into the row's half spectrum X[k], k in [0, L]. It is written transposed
//    (column-major: L + 1 columns of ny values), so the column pass reads contiguous lines.
//    The padding rows ny..my are never stored: they are zero.
// 2. `columns`: each column is transformed along y, multiplied by the real symbol and
//    transformed back; only the ny kept rows are computed (the crop). Periodic filters
//    (my = ny) do this directly. Padded ones (my = 2ny) split the 2ny-point transform of a
//    column whose upper half is zero into its even and odd frequencies:
//        X[2m] = FFT_ny(x)[m],   X[2m+1] = FFT_ny(x·w)[m],   w_j = e^{−2πij/2ny},
//    and on the way back y_j = IFFT_ny(Y_even)[j] + conj(w_j)·IFFT_ny(Y_odd)[j] for j < ny:
//    two ny-point chains instead of one 2ny-point transform, so no line is ever longer than
//    the grid's own side and none leaves workgroup memory.
// 3. `rows_inverse`: each kept row gathers its half spectrum, merges it back into L complex
//    values, transforms them back and unpacks the first nx real values; masked (the
//    preconditioner), it writes zero off the contact set; optionally it adds Σ dst·other
//    into a pending slot (a CG dot product for free: `dst` is still in registers).
//
// The symbol carries the normalisation 1/(L·my). `fft_lines` transforms lines in place (for
// tests and benches of the FFT itself).
//
// CPU twin: `jkrbem::backend::gpu::twin` (the same three passes in f64), itself checked
// against `jkrbem::backend::cpu::spectral::SpectralFilter` (realfft/rustfft).

// Must stay in sync with `SpectralParams` in src/backend/gpu/spectral.rs.
struct Params {
    // Data shape nx × ny (real values, row-major).
    nx: u32,
    ny: u32,
    // log2 of the row FFT length L = mx / 2 (nx padded, nx / 2 periodic).
    log_l: u32,
    // log2 of rows per workgroup in rows_forward / rows_inverse.
    log_rows: u32,
    // log2(ny): the column chain length.
    log_ny: u32,
    // log2 of columns per workgroup in `columns`.
    log_cols: u32,
    // 1: the transform is 2nx × 2ny (zero padded, cropped); 0: periodic nx × ny.
    padded: u32,
    // 1: rows_forward reads src as zero off the contact mask, rows_inverse writes zero there.
    masked: u32,
    // rows_inverse: slot receiving Σ dst·other over the grid (NO_SLOT: none).
    dot_slot: u32,
    // fft_lines: number of lines, and 1 for the inverse transform.
    lines: u32,
    inverse: u32,
    // 1: part of a guarded CG batch (return at once once it has stopped).
    guarded: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
// rows_forward's parameters, the same struct in a storage buffer (see rows_forward).
@group(0) @binding(9) var<storage, read> forward_params: Params;
// Real field nx × ny as pairs (x[2k], x[2k+1]) (rows_forward's input).
@group(0) @binding(1) var<storage, read> src: array<vec2<f32>>;
// Contact mask as pairs (1 = in contact).
@group(0) @binding(2) var<storage, read> mask: array<vec2<u32>>;
// Half spectrum, column-major: column k (k in [0, L]) holds ny values at [k·ny, (k + 1)·ny).
@group(0) @binding(3) var<storage, read_write> spec: array<vec2<f32>>;
// Real symbol: periodic, column k at [k·ny, (k + 1)·ny); padded, the even frequencies of
// column k at [2k·ny, (2k + 1)·ny) and the odd ones at [(2k + 1)·ny, (2k + 2)·ny).
@group(0) @binding(5) var<storage, read> symbol: array<f32>;
// Real field nx × ny as pairs (rows_inverse's output).
@group(0) @binding(6) var<storage, read_write> dst: array<vec2<f32>>;
// Real field nx × ny as pairs: the other factor of rows_inverse's dot product.
@group(0) @binding(7) var<storage, read> other: array<vec2<f32>>;

fn group_index(wid: vec3<u32>, nwg: vec3<u32>) -> u32 {
    return wid.x + wid.y * nwg.x;
}

@compute @workgroup_size(WG)
fn rows_forward(
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    // The parameters come from a storage buffer: Mesa's lavapipe (22.3) compiled a new
    // variant of this kernel, inlining its uniform parameters, at every dispatch and never
    // freed it (0.7 MB per dispatch at 64²).
    let prm = forward_params;
    if prm.guarded != 0u && cg_halted(lid) {
        return;
    }
    let log_l = prm.log_l;
    let l = 1u << log_l;
    let log_g = prm.log_rows;
    let npts = l << log_g;
    let row0 = group_index(wid, nwg) << log_g;
    let pairs = prm.nx >> 1u;
    for (var c = 0u; c < VPT; c++) {
        let p = lid + c * WG;
        if p < npts {
            let j = row0 + (p >> log_l);
            let k = p & (l - 1u);
            var z = vec2<f32>(0.0, 0.0);
            if j < prm.ny && k < pairs {
                // The pair (x[2k], x[2k+1]) of row j, zero off the contact when masked. (Written
                // out here rather than in a function: Mesa's lavapipe leaked memory at every
                // dispatch of the function form.)
                let idx = j * pairs + k;
                z = src[idx];
                if prm.masked != 0u {
                    let m = mask[idx];
                    z = vec2<f32>(select(0.0, z.x, m.x != 0u), select(0.0, z.y, m.y != 0u));
                }
            }
            buf[at(p)] = z;
        }
    }
    workgroupBarrier();
    fft_lines_in_buf(lid, log_l, npts, false);
    // X[k] = E + e^{−2πik/2L}·O, E = (Z[k] + conj Z[L−k])/2, O = (Z[k] − conj Z[L−k])/(2i);
    // consecutive threads take consecutive rows of one column (runs of 2^log_g values).
    let ny = prm.ny;
    let nout = (l + 1u) << log_g;
    for (var q = lid; q < nout; q += WG) {
        let g = q & ((1u << log_g) - 1u);
        let k = q >> log_g;
        let j = row0 + g;
        if j < ny {
            let line = g << log_l;
            let zk = buf[at(line + (k & (l - 1u)))];
            let zc = conj(buf[at(line + ((l - k) & (l - 1u)))]);
            let e = 0.5 * (zk + zc);
            let d = 0.5 * (zk - zc);
            let o = vec2<f32>(d.y, -d.x);
            spec[k * ny + j] = e + cmul(twiddle_at(k, log_l + 1u, false), o);
        }
    }
}

@compute @workgroup_size(WG)
fn columns(
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    if params.guarded != 0u && cg_halted(lid) {
        return;
    }
    let log_n = params.log_ny;
    let n = 1u << log_n;
    let log_g = params.log_cols;
    let npts = n << log_g;
    let col0 = group_index(wid, nwg) << log_g;
    let ncols = (1u << params.log_l) + 1u;
    var x: array<vec2<f32>, VPT>;
    for (var c = 0u; c < VPT; c++) {
        let p = lid + c * WG;
        let k = col0 + (p >> log_n);
        if p < npts && k < ncols {
            x[c] = spec[(k << log_n) + (p & (n - 1u))];
        } else {
            x[c] = vec2<f32>(0.0, 0.0);
        }
    }
    if params.padded == 0u {
        for (var c = 0u; c < VPT; c++) {
            let p = lid + c * WG;
            if p < npts {
                buf[at(p)] = x[c];
            }
        }
        workgroupBarrier();
        fft_lines_in_buf(lid, log_n, npts, false);
        for (var c = 0u; c < VPT; c++) {
            let p = lid + c * WG;
            let k = col0 + (p >> log_n);
            if p < npts && k < ncols {
                buf[at(p)] = buf[at(p)] * symbol[(k << log_n) + (p & (n - 1u))];
            }
        }
        workgroupBarrier();
        fft_lines_in_buf(lid, log_n, npts, true);
        for (var c = 0u; c < VPT; c++) {
            let p = lid + c * WG;
            let k = col0 + (p >> log_n);
            if p < npts && k < ncols {
                spec[(k << log_n) + (p & (n - 1u))] = buf[at(p)];
            }
        }
        return;
    }
    // Padded: the even frequencies first, kept in registers as a.
    var a: array<vec2<f32>, VPT>;
    for (var parity = 0u; parity < 2u; parity++) {
        for (var c = 0u; c < VPT; c++) {
            let p = lid + c * WG;
            if p < npts {
                var v = x[c];
                if parity == 1u {
                    v = cmul(v, twiddle_at(p & (n - 1u), log_n + 1u, false));
                }
                buf[at(p)] = v;
            }
        }
        workgroupBarrier();
        fft_lines_in_buf(lid, log_n, npts, false);
        for (var c = 0u; c < VPT; c++) {
            let p = lid + c * WG;
            let k = col0 + (p >> log_n);
            if p < npts && k < ncols {
                buf[at(p)] = buf[at(p)] * symbol[((2u * k + parity) << log_n) + (p & (n - 1u))];
            }
        }
        workgroupBarrier();
        fft_lines_in_buf(lid, log_n, npts, true);
        for (var c = 0u; c < VPT; c++) {
            let p = lid + c * WG;
            if p < npts {
                if parity == 0u {
                    a[c] = buf[at(p)];
                } else {
                    let k = col0 + (p >> log_n);
                    if k < ncols {
                        let w = twiddle_at(p & (n - 1u), log_n + 1u, true);
                        spec[(k << log_n) + (p & (n - 1u))] = a[c] + cmul(w, buf[at(p)]);
                    }
                }
            }
        }
        workgroupBarrier();
    }
}

// X[L] of each row of the workgroup (the Nyquist column), beside buf's X[0..L).
var<workgroup> nyquist: array<vec2<f32>, WG>;

@compute @workgroup_size(WG)
fn rows_inverse(
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    if params.guarded != 0u && cg_halted(lid) {
        return;
    }
    let log_l = params.log_l;
    let l = 1u << log_l;
    let log_g = params.log_rows;
    let npts = l << log_g;
    let group = group_index(wid, nwg);
    let row0 = group << log_g;
    let ny = params.ny;
    let nin = (l + 1u) << log_g;
    for (var q = lid; q < nin; q += WG) {
        let g = q & ((1u << log_g) - 1u);
        let k = q >> log_g;
        let j = row0 + g;
        var v = vec2<f32>(0.0, 0.0);
        if j < ny {
            v = spec[k * ny + j];
        }
        if k < l {
            buf[at((g << log_l) + k)] = v;
        } else {
            nyquist[g] = v;
        }
    }
    workgroupBarrier();
    // Z[k] = E + i·O, E = (X[k] + conj X[L−k])/2, O = (X[k] − conj X[L−k])·e^{+2πik/2L}/2.
    var z: array<vec2<f32>, VPT>;
    for (var c = 0u; c < VPT; c++) {
        let p = lid + c * WG;
        if p < npts {
            let g = p >> log_l;
            let k = p & (l - 1u);
            let xk = buf[at(p)];
            var xc = nyquist[g];
            if k != 0u {
                xc = buf[at((g << log_l) + l - k)];
            }
            xc = conj(xc);
            let e = 0.5 * (xk + xc);
            let o = cmul(0.5 * (xk - xc), twiddle_at(k, log_l + 1u, true));
            z[c] = e + vec2<f32>(-o.y, o.x);
        }
    }
    workgroupBarrier();
    for (var c = 0u; c < VPT; c++) {
        let p = lid + c * WG;
        if p < npts {
            buf[at(p)] = z[c];
        }
    }
    workgroupBarrier();
    fft_lines_in_buf(lid, log_l, npts, true);
    let pairs = params.nx >> 1u;
    var acc = 0.0;
    for (var c = 0u; c < VPT; c++) {
        let p = lid + c * WG;
        let j = row0 + (p >> log_l);
        let k = p & (l - 1u);
        if p < npts && j < ny && k < pairs {
            let idx = j * pairs + k;
            var v = buf[at(p)];
            if params.masked != 0u {
                let m = mask[idx];
                v = vec2<f32>(select(0.0, v.x, m.x != 0u), select(0.0, v.y, m.y != 0u));
            }
            dst[idx] = v;
            if params.dot_slot != NO_SLOT {
                acc += dot(v, other[idx]);
            }
        }
    }
    if params.dot_slot != NO_SLOT {
        slot_partial(lid, params.dot_slot, acc, group, (ny + (1u << log_g) - 1u) >> log_g);
    }
}

@compute @workgroup_size(WG)
fn fft_lines(
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    let log_l = params.log_l;
    let log_g = params.log_rows;
    let npts = 1u << (log_l + log_g);
    let base = group_index(wid, nwg) * npts;
    let total = params.lines << log_l;
    for (var c = 0u; c < VPT; c++) {
        let p = lid + c * WG;
        if p < npts && base + p < total {
            buf[at(p)] = spec[base + p];
        }
    }
    workgroupBarrier();
    fft_lines_in_buf(lid, log_l, npts, params.inverse != 0u);
    for (var c = 0u; c < VPT; c++) {
        let p = lid + c * WG;
        if p < npts && base + p < total {
            spec[base + p] = buf[at(p)];
        }
    }
}
