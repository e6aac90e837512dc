// Batched complex-to-complex radix-2 Stockham autosort FFT on f32.
//
// A complex value is a vec2<f32> (x = real, y = imaginary). Lines of length n (a power of two)
// lie contiguously, one after another. The forward transform is X[k] = Σ x[j] e^{-2πi jk/n};
// the inverse uses e^{+2πi jk/n} and is unnormalised (like rustfft).
//
// Stockham stage with stride s (s = 1, 2, 4, …, n/2) and current length L = n/s, m = L/2:
// for every butterfly j in [0, n/2), p = j / s, q = j % s,
//     a = x[j],  b = x[j + n/2],  w = e^{-2πi p / L}
//     y[q + 2sp]     = a + b
//     y[q + 2sp + s] = (a − b)·w
// After the stage the elements ≡ q (mod 2s) form independent lines of length L/2, so once
// L ≤ SMEM the rest of the transform of each residue q runs in workgroup memory
// (`fft_shared`); the stages before that run in global memory, one per dispatch
// (`fft_global_stage`). CPU twin: `jkrbem::backend::gpu::fft::stockham_twin`.
//
// The host substitutes SMEM (the largest line held in workgroup memory) before compiling, and
// appends `fft_shared_oop`: a copy of `fft_shared` (the last function of this file) that loads
// from `src` and stores to `dst`, so an odd number of global stages needs no copy back.

// Must stay in sync with `FftParams` in src/backend/gpu/fft.rs.
struct Params {
    // Line length n (complex values).
    n: u32,
    // Number of lines.
    batch: u32,
    // Stride s of the stage (`fft_global_stage`) or of the sub-lines (`fft_shared`).
    stride: u32,
    // Length of the twiddle table's full circle: twiddle[k] = e^{-2πi k / n_max}.
    n_max: u32,
    // 1 for the inverse transform, 0 for the forward one.
    inverse: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

const SMEM: u32 = __SMEM__u;
const WG: u32 = 256u;

@group(0) @binding(0) var<uniform> params: Params;
// twiddle[k] = e^{-2πi k / n_max}, k in [0, n_max/2), computed on the host in f64.
@group(0) @binding(1) var<storage, read> twiddle: array<vec2<f32>>;
// Lines transformed in place by `fft_shared`.
@group(0) @binding(2) var<storage, read_write> data: array<vec2<f32>>;
// Source and destination of one global-memory stage.
@group(0) @binding(3) var<storage, read> src: array<vec2<f32>>;
@group(0) @binding(4) var<storage, read_write> dst: array<vec2<f32>>;

// Two ping-pong buffers of SMEM complex values: 16·SMEM bytes of workgroup memory.
var<workgroup> buf: array<array<vec2<f32>, SMEM>, 2>;

fn cmul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

// e^{∓2πi p / len} for len = 2^log_len: the forward (−) or inverse (+) twiddle of a stage.
// Every length is a power of two, so indices use shifts and masks instead of divisions.
fn twiddle_for(p: u32, log_len: u32) -> vec2<f32> {
    let w = twiddle[p << (countTrailingZeros(params.n_max) - log_len)];
    return select(w, vec2<f32>(w.x, -w.y), params.inverse != 0u);
}

// One radix-2 Stockham stage over whole lines in global memory; one thread per butterfly.
@compute @workgroup_size(WG)
fn fft_global_stage(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    let half = params.n / 2u;
    let idx = gid.x + gid.y * nwg.x * WG;
    if idx >= params.batch * half {
        return;
    }
    let log_half = countTrailingZeros(half);
    let line = idx >> log_half;
    let j = idx & (half - 1u);
    let s = params.stride;
    let log_s = countTrailingZeros(s);
    let p = j >> log_s;
    let q = j & (s - 1u);
    let base = line * params.n;
    let a = src[base + j];
    let b = src[base + j + half];
    let w = twiddle_for(p, log_half + 1u - log_s);
    dst[base + q + 2u * s * p] = a + b;
    dst[base + q + 2u * s * p + s] = cmul(a - b, w);
}

// The remaining stages of sub-lines (elements line·n + q + stride·i, i in [0, n/stride)) in
// workgroup memory. Sub-line g = line·stride + q; one workgroup takes LPG consecutive
// sub-lines, LPG = max(1, min(2·WG, SMEM) / len), so short lines keep every thread busy.
@compute @workgroup_size(WG)
fn fft_shared(
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
) {
    let stride = params.stride;
    let log_stride = countTrailingZeros(stride);
    let log_n = countTrailingZeros(params.n);
    let log_len = log_n - log_stride;
    let len = 1u << log_len;
    let lpg = max(1u, min(2u * WG, SMEM) >> log_len);
    let g0 = (wid.x + wid.y * nwg.x) * lpg;
    let total = params.batch * stride;
    let half = len / 2u;
    let log_half = log_len - 1u;

    for (var t = lid; t < lpg * len; t += WG) {
        let g = g0 + (t >> log_len);
        if g < total {
            let at = ((g >> log_stride) << log_n) + (g & (stride - 1u)) + ((t & (len - 1u)) << log_stride);
            buf[0][t] = data[at];
        }
    }
    workgroupBarrier();

    var cur = 0u;
    var log_s = 0u;
    loop {
        if log_s >= log_len {
            break;
        }
        let s = 1u << log_s;
        let nxt = 1u - cur;
        for (var t = lid; t < lpg * half; t += WG) {
            let base = (t >> log_half) << log_len;
            let j = t & (half - 1u);
            let p = j >> log_s;
            let q = j & (s - 1u);
            let a = buf[cur][base + j];
            let b = buf[cur][base + j + half];
            let w = twiddle_for(p, log_len - log_s);
            let o = base + q + ((p << log_s) << 1u);
            buf[nxt][o] = a + b;
            buf[nxt][o + s] = cmul(a - b, w);
        }
        workgroupBarrier();
        cur = nxt;
        log_s += 1u;
    }

    for (var t = lid; t < lpg * len; t += WG) {
        let g = g0 + (t >> log_len);
        if g < total {
            let at = ((g >> log_stride) << log_n) + (g & (stride - 1u)) + ((t & (len - 1u)) << log_stride);
            data[at] = buf[cur][t];
        }
    }
}
