// Shared by the spectral kernels: a workgroup-memory FFT of G lines of L complex f32 values
// (L a power of two, G·L ≤ POINTS_MAX), in radix-8 Stockham passes with a radix-4 or radix-2
// pass last (Govindaraju et al. 2008): at a pass of radix R after sub-transforms of size Ns,
// butterfly j (j < L/R) of a line reads v[r] = x[j + r·L/R], multiplies v[r] by w^r with
// w = e^{∓2πi (j mod Ns)/(Ns·R)}, takes the R-point DFT, and writes v[r] to
// y[(j − j mod Ns)·R + j mod Ns + r·Ns]. Every thread loads its butterflies' values into
// registers, the workgroup meets at a barrier, and the thread writes them back: one buffer
// of POINTS_MAX values and two barriers per pass (4 passes for L = 2048 instead of 11).
// The forward transform uses e^{−2πi jk/L}; the inverse e^{+2πi jk/L}, unnormalised.
//
// Twiddles come from a table e^{−2πik/TWIDDLE_LEN} (computed in f64 on the host): one load
// per butterfly and pass, its powers w^r by complex multiplication.
//
// CPU twin: `jkrbem::backend::gpu::twin::fft_lines` (the same passes in f64).

// The line set's size: `VPT` values per thread, `POINTS_MAX` = VPT·WG values per workgroup,
// come from shared/points_2048.wgsl or shared/points_4096.wgsl, whichever the module is built
// with (fewer values per thread keep fewer registers live: more workgroups per multiprocessor).

// Length of the twiddle table's full circle (twice the longest line of any variant: the
// real-FFT split needs e^{−2πik/2L}).
const TWIDDLE_LEN: u32 = 8192u;

// twiddle[k] = e^{−2πik/TWIDDLE_LEN}, k in [0, TWIDDLE_LEN).
@group(0) @binding(4) var<storage, read> twiddle: array<vec2<f32>>;

// The lines being transformed: value i of the set (line g holds i in [g·L, (g + 1)·L)) lives at
// buf[at(i)], one spare cell after every eight, so that the strided stores of the first
// passes (stride 8 and 64 values) fall in different memory banks.
var<workgroup> buf: array<vec2<f32>, POINTS_MAX + POINTS_MAX / 8u>;

fn at(i: u32) -> u32 {
    return i + (i >> 3u);
}

fn cmul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

fn conj(a: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x, -a.y);
}

// i·a (inverse) or −i·a (forward).
fn rot(a: vec2<f32>, inverse: bool) -> vec2<f32> {
    return select(vec2<f32>(a.y, -a.x), vec2<f32>(-a.y, a.x), inverse);
}

// e^{∓2πi k / 2^log_n} (− forward, + inverse), for 2^log_n ≤ TWIDDLE_LEN and k < 2^log_n.
fn twiddle_at(k: u32, log_n: u32, inverse: bool) -> vec2<f32> {
    let w = twiddle[k << (countTrailingZeros(TWIDDLE_LEN) - log_n)];
    return select(w, conj(w), inverse);
}

// The 4-point DFT (a, b, c, d) of (x0, x1, x2, x3).
struct Four {
    a: vec2<f32>,
    b: vec2<f32>,
    c: vec2<f32>,
    d: vec2<f32>,
}

fn dft4(x0: vec2<f32>, x1: vec2<f32>, x2: vec2<f32>, x3: vec2<f32>, inverse: bool) -> Four {
    let t0 = x0 + x2;
    let t1 = x0 - x2;
    let t2 = x1 + x3;
    let t3 = rot(x1 - x3, inverse);
    return Four(t0 + t2, t1 + t3, t0 - t2, t1 - t3);
}

// The butterfly j of a line (b = line·L/R + j), the start of its line, and m = j mod ns.
struct Butterfly {
    line: u32,
    j: u32,
    m: u32,
}

fn butterfly(b: u32, log_l: u32, log_lr: u32, ns: u32) -> Butterfly {
    let j = b & ((1u << log_lr) - 1u);
    return Butterfly((b >> log_lr) << log_l, j, j & (ns - 1u));
}

// Eight values of one radix-8 butterfly, named so that every register is a constant.
struct V8 {
    x0: vec2<f32>,
    x1: vec2<f32>,
    x2: vec2<f32>,
    x3: vec2<f32>,
    x4: vec2<f32>,
    x5: vec2<f32>,
    x6: vec2<f32>,
    x7: vec2<f32>,
}

// The radix-8 DFT of v·(1, w, w², …, w⁷).
fn dft8(v: V8, w1: vec2<f32>, inverse: bool) -> V8 {
    let w2 = cmul(w1, w1);
    let w3 = cmul(w2, w1);
    let w4 = cmul(w2, w2);
    let e = dft4(v.x0, cmul(v.x2, w2), cmul(v.x4, w4), cmul(v.x6, cmul(w4, w2)), inverse);
    let d = dft4(cmul(v.x1, w1), cmul(v.x3, w3), cmul(v.x5, cmul(w4, w1)), cmul(v.x7, cmul(w4, w3)), inverse);
    // d_k · e^{∓2πik/8}, k = 1, 2, 3.
    let h = 0.70710678118654752;
    let s = select(-1.0, 1.0, inverse);
    let d1 = cmul(d.b, vec2<f32>(h, s * h));
    let d2 = rot(d.c, inverse);
    let d3 = cmul(d.d, vec2<f32>(-h, s * h));
    return V8(e.a + d.a, e.b + d1, e.c + d2, e.d + d3, e.a - d.a, e.b - d1, e.c - d2, e.d - d3);
}

// The three passes below are one pass of radix R = 8, 4, 2 over `npts` = G·L values
// (L = 2^log_l) after sub-transforms of size ns; each thread loads its VPT / R butterflies
// into registers, the workgroup meets at a barrier, each thread stores its results, and the
// workgroup meets again. Called by every thread, in uniform control flow.

fn fft_pass8(lid: u32, log_l: u32, npts: u32, ns: u32, inverse: bool) {
    var v: array<V8, VPT / 8u>;
    let log_lr = log_l - 3u;
    let nb = npts >> 3u;
    let q = 1u << log_lr;
    for (var c = 0u; c < VPT / 8u; c++) {
        let b = lid + c * WG;
        if b < nb {
            let f = butterfly(b, log_l, log_lr, ns);
            let i = f.line + f.j;
            v[c] = V8(
                buf[at(i)], buf[at(i + q)], buf[at(i + 2u * q)], buf[at(i + 3u * q)],
                buf[at(i + 4u * q)], buf[at(i + 5u * q)], buf[at(i + 6u * q)], buf[at(i + 7u * q)],
            );
        }
    }
    workgroupBarrier();
    for (var c = 0u; c < VPT / 8u; c++) {
        let b = lid + c * WG;
        if b < nb {
            let f = butterfly(b, log_l, log_lr, ns);
            let y = dft8(v[c], twiddle_at(f.m, countTrailingZeros(ns) + 3u, inverse), inverse);
            let o = f.line + ((f.j - f.m) << 3u) + f.m;
            buf[at(o)] = y.x0;
            buf[at(o + ns)] = y.x1;
            buf[at(o + 2u * ns)] = y.x2;
            buf[at(o + 3u * ns)] = y.x3;
            buf[at(o + 4u * ns)] = y.x4;
            buf[at(o + 5u * ns)] = y.x5;
            buf[at(o + 6u * ns)] = y.x6;
            buf[at(o + 7u * ns)] = y.x7;
        }
    }
    workgroupBarrier();
}

fn fft_pass4(lid: u32, log_l: u32, npts: u32, ns: u32, inverse: bool) {
    var v: array<Four, VPT / 4u>;
    let log_lr = log_l - 2u;
    let nb = npts >> 2u;
    let q = 1u << log_lr;
    for (var c = 0u; c < VPT / 4u; c++) {
        let b = lid + c * WG;
        if b < nb {
            let f = butterfly(b, log_l, log_lr, ns);
            let i = f.line + f.j;
            v[c] = Four(buf[at(i)], buf[at(i + q)], buf[at(i + 2u * q)], buf[at(i + 3u * q)]);
        }
    }
    workgroupBarrier();
    for (var c = 0u; c < VPT / 4u; c++) {
        let b = lid + c * WG;
        if b < nb {
            let f = butterfly(b, log_l, log_lr, ns);
            let w1 = twiddle_at(f.m, countTrailingZeros(ns) + 2u, inverse);
            let w2 = cmul(w1, w1);
            let x = v[c];
            let y = dft4(x.a, cmul(x.b, w1), cmul(x.c, w2), cmul(x.d, cmul(w2, w1)), inverse);
            let o = f.line + ((f.j - f.m) << 2u) + f.m;
            buf[at(o)] = y.a;
            buf[at(o + ns)] = y.b;
            buf[at(o + 2u * ns)] = y.c;
            buf[at(o + 3u * ns)] = y.d;
        }
    }
    workgroupBarrier();
}

fn fft_pass2(lid: u32, log_l: u32, npts: u32, ns: u32, inverse: bool) {
    var v: array<vec4<f32>, VPT / 2u>;
    let log_lr = log_l - 1u;
    let nb = npts >> 1u;
    let q = 1u << log_lr;
    for (var c = 0u; c < VPT / 2u; c++) {
        let b = lid + c * WG;
        if b < nb {
            let f = butterfly(b, log_l, log_lr, ns);
            let i = f.line + f.j;
            v[c] = vec4<f32>(buf[at(i)], buf[at(i + q)]);
        }
    }
    workgroupBarrier();
    for (var c = 0u; c < VPT / 2u; c++) {
        let b = lid + c * WG;
        if b < nb {
            let f = butterfly(b, log_l, log_lr, ns);
            let t = cmul(v[c].zw, twiddle_at(f.m, countTrailingZeros(ns) + 1u, inverse));
            let o = f.line + ((f.j - f.m) << 1u) + f.m;
            buf[at(o)] = v[c].xy + t;
            buf[at(o + ns)] = v[c].xy - t;
        }
    }
    workgroupBarrier();
}

// Transform the `npts` / L lines of length L = 2^log_l held in `buf`, in place. Radix-8
// passes while three or more factors of two are left, then one radix-4 or radix-2 pass.
// Called by every thread, in uniform control flow; buf must be complete (after a barrier).
fn fft_lines_in_buf(lid: u32, log_l: u32, npts: u32, inverse: bool) {
    var ns = 1u;
    var left = log_l;
    loop {
        if left == 0u {
            break;
        }
        if left >= 3u {
            fft_pass8(lid, log_l, npts, ns, inverse);
            ns = ns << 3u;
            left -= 3u;
        } else if left == 2u {
            fft_pass4(lid, log_l, npts, ns, inverse);
            ns = ns << 2u;
            left = 0u;
        } else {
            fft_pass2(lid, log_l, npts, ns, inverse);
            ns = ns << 1u;
            left = 0u;
        }
    }
}
