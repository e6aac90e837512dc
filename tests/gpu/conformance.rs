//! The backend contract, checked the same way on every backend (cpu, cpu-periodic, gpu,
//! gpu-periodic): each operation against its definition in `backend/mod.rs`, computed here on
//! the host in f64.
//!
//! Values that the contract says do not matter (off the contact set C) are filled with NaN, so
//! an operation that should write zeros off C, or should read only C, cannot pass by accident:
//! a NaN read where it should not be shows up in the result. The convolution is compared with
//! the CPU backend of the same convolution (padded or periodic: the periodic one is itself
//! checked against Love's kernel summed over the images in `backend::kernel`'s tests and
//! against the continuum and the padded one in `tests/backend/periodic.rs`), the
//! preconditioner with the CPU one. The periodic backends report no contact at the edge and
//! certify nothing.
//!
//! The GPU backend's checks are reported as ignored, with the reason, where no GPU adapter
//! exists, and fail instead with `JKRBEM_REQUIRE_GPU=1`.

use crate::common;

use common::pseudo_random;
use jkrbem::backend::cpu::CpuBackend;
use jkrbem::backend::measure::measure_mask;
use jkrbem::backend::prelude::*;
use jkrbem::backend::{CgStop, ChordAxes, GridSetup, Preconditioner};
use libtest_mimic::Trial;

/// Elements along x and y: rectangular, so that a transposed index shows.
const NX: usize = 32;
const NY: usize = 16;

/// The setup every check uses: a rough profile (so that gaps have both signs).
fn setup() -> GridSetup {
    GridSetup {
        nx: NX,
        ny: NY,
        dx: 0.05,
        e_star: 1.7,
        profile: pseudo_random(NX * NY, 99).iter().map(|v| 0.3 + v).collect(),
        preconditioner: Preconditioner::Stiffness,
    }
}

/// A mask with about half of the elements in contact.
fn mask() -> Vec<bool> {
    pseudo_random(NX * NY, 7).iter().map(|v| *v < 0.0).collect()
}

/// `values` on C, NaN off C.
fn poisoned(values: &[f64], mask: &[bool]) -> Vec<f64> {
    values
        .iter()
        .zip(mask)
        .map(|(&v, &m)| if m { v } else { f64::NAN })
        .collect()
}

/// `values` on C, 0 off C.
fn on_c(values: &[f64], mask: &[bool]) -> Vec<f64> {
    values
        .iter()
        .zip(mask)
        .map(|(&v, &m)| if m { v } else { 0.0 })
        .collect()
}

/// What a check needs: the backend under test and its tolerance (relative to the values'
/// scale: its arithmetic's rounding times a margin for sums of a few hundred terms).
struct Subject<B: Backend> {
    b: B,
    tol: f64,
    /// The contact set on the host, and on the backend's device.
    mask: Vec<bool>,
    c: B::Mask,
}

impl<B: Backend> Subject<B> {
    fn new(b: B) -> Self {
        let tol = if b.precision() == "f64" { 1e-12 } else { 2e-5 };
        let mut b = b;
        let mask = mask();
        let mut c = b.mask().unwrap();
        b.upload_mask(&mut c, &mask).unwrap();
        Subject { b, tol, mask, c }
    }

    fn put(&mut self, host: &[f64]) -> B::Field {
        let mut f = self.b.field().unwrap();
        self.b.upload(&mut f, host).unwrap();
        f
    }

    fn get(&mut self, f: &B::Field) -> Vec<f64> {
        let mut out = vec![0.0; NX * NY];
        self.b.download(f, &mut out).unwrap();
        out
    }

    fn slots(&mut self, n: usize) -> Vec<jkrbem::backend::Slot> {
        (0..n).map(|_| self.b.slot().unwrap()).collect()
    }

    fn read(&mut self, slot: jkrbem::backend::Slot) -> f64 {
        let mut v = [0.0];
        self.b.read_slots(&[slot], &mut v).unwrap();
        v[0]
    }

    /// Every value finite and within tolerance of `want` (NaN never passes).
    fn assert_close(&self, what: &str, got: &[f64], want: &[f64]) {
        let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
        for (i, (g, w)) in got.iter().zip(want).enumerate() {
            assert!(
                g.is_finite() && (g - w).abs() <= self.tol * scale,
                "{what}: element {i} (x {}, y {}) is {g}, expected {w}",
                i % NX,
                i / NX
            );
        }
    }

    fn assert_scalar(&self, what: &str, got: f64, want: f64, scale: f64) {
        assert!(
            got.is_finite() && (got - want).abs() <= self.tol * scale.max(want.abs()),
            "{what}: {got}, expected {want}"
        );
    }
}

/// A new field is zero; upload and download round-trip; copy copies the whole grid.
fn fields_and_copy<B: Backend>(mut s: Subject<B>) {
    let zero = s.b.field().unwrap();
    let z = s.get(&zero);
    s.assert_close("field()", &z, &vec![0.0; NX * NY]);
    let a = pseudo_random(NX * NY, 1);
    let fa = s.put(&a);
    let back = s.get(&fa);
    s.assert_close("upload/download", &back, &a);
    let mut dst = s.put(&vec![f64::NAN; NX * NY]);
    s.b.copy(&fa, &mut dst).unwrap();
    let c = s.get(&dst);
    s.assert_close("copy", &c, &a);
}

/// Registers start at 0, copy_slot copies, and a dot product lands in its own register.
fn slots<B: Backend>(mut s: Subject<B>) {
    let r = s.slots(3);
    assert_eq!(s.read(r[2]), 0.0, "a new slot holds 0");
    let a = pseudo_random(NX * NY, 3);
    let fa = s.put(&a);
    s.b.dot(&s.c, &fa, &fa, r[0]).unwrap();
    s.b.copy_slot(r[0], r[1]).unwrap();
    let want: f64 = on_c(&a, &s.mask).iter().map(|v| v * v).sum();
    let (got0, got1) = (s.read(r[0]), s.read(r[1]));
    s.assert_scalar("dot into its slot", got0, want, want);
    s.assert_scalar("copy_slot", got1, want, want);
    assert_eq!(s.read(r[2]), 0.0, "an unwritten slot still holds 0");
}

/// r = d − h − u on C, 0 off C, with u NaN off C and r NaN before.
fn residual<B: Backend>(mut s: Subject<B>) {
    let h = setup().profile;
    let u = pseudo_random(NX * NY, 2);
    let fu = s.put(&poisoned(&u, &s.mask));
    let mut r = s.put(&vec![f64::NAN; NX * NY]);
    let d = 0.7;
    s.b.residual(&s.c, &fu, d, &mut r).unwrap();
    let want: Vec<f64> = (0..NX * NY)
        .map(|i| if s.mask[i] { d - h[i] - u[i] } else { 0.0 })
        .collect();
    let got = s.get(&r);
    s.assert_close("residual", &got, &want);
}

/// Σ_C a·b with a and b NaN off C.
fn reductions<B: Backend>(mut s: Subject<B>) {
    let (a, b) = (pseudo_random(NX * NY, 4), pseudo_random(NX * NY, 5));
    let fa = s.put(&poisoned(&a, &s.mask));
    let fb = s.put(&poisoned(&b, &s.mask));
    let out = s.slots(1)[0];
    s.b.dot(&s.c, &fa, &fb, out).unwrap();
    let (ca, cb) = (on_c(&a, &s.mask), on_c(&b, &s.mask));
    let want: f64 = ca.iter().zip(&cb).map(|(x, y)| x * y).sum();
    let scale: f64 = ca.iter().zip(&cb).map(|(x, y)| (x * y).abs()).sum();
    let got = s.read(out);
    s.assert_scalar("dot", got, want, scale);
}

/// A state's measurement: Σ_C p with p NaN off C, |C|, the chords along the grid's axes
/// (exact) and along axes turned by 30° and 135° (f32's rounding of the band areas), and the
/// index box; an empty C has none.
fn measure<B: Backend>(mut s: Subject<B>) {
    let a = pseudo_random(NX * NY, 4);
    let fa = s.put(&poisoned(&a, &s.mask));
    let ca = on_c(&a, &s.mask);
    let scale: f64 = ca.iter().map(|v| v.abs()).sum();
    for deg in [0.0, 30.0, 135.0f64] {
        let (sin, cos) = deg.to_radians().sin_cos();
        let axes = if deg == 0.0 {
            ChordAxes::ALIGNED
        } else {
            ChordAxes { cos, sin }
        };
        let got = s.b.measure(&s.c, &fa, axes).unwrap();
        let want = measure_mask(&ca, &s.mask, NX, NY, axes);
        s.assert_scalar("measure sum", got.sum, want.sum, scale);
        assert_eq!(got.count, want.count, "count");
        assert_eq!(got.bounds, want.bounds, "index box");
        let chord_tol = if deg == 0.0 { 0.0 } else { 1e-3 };
        for (g, w) in [
            (got.half_lengths.0, want.half_lengths.0),
            (got.half_lengths.1, want.half_lengths.1),
        ] {
            assert!(
                (g - w).abs() <= chord_tol * (1.0 + w),
                "chords at {deg}°: {:?}, expected {:?}",
                got.half_lengths,
                want.half_lengths
            );
        }
    }
    // One element in contact at (5, 3): its box, and no box without contact.
    let mut one = vec![false; NX * NY];
    one[3 * NX + 5] = true;
    s.b.upload_mask(&mut s.c, &one).unwrap();
    let got = s.b.measure(&s.c, &fa, ChordAxes::ALIGNED).unwrap();
    assert_eq!((got.count, got.bounds), (1, Some([5, 5, 3, 3])));
    s.b.upload_mask(&mut s.c, &vec![false; NX * NY]).unwrap();
    let got = s.b.measure(&s.c, &fa, ChordAxes::ALIGNED).unwrap();
    assert_eq!((got.sum, got.count, got.bounds), (0.0, 0, None));
}

/// copy_mask keeps C in another set, which brings it back after C has changed; a new set is
/// empty.
fn save_and_restore_contact<B: Backend>(mut s: Subject<B>) {
    let mut kept = s.b.mask().unwrap();
    let mut empty = vec![true; NX * NY];
    s.b.download_mask(&kept, &mut empty).unwrap();
    assert!(empty.iter().all(|&m| !m), "a new contact set is empty");
    s.b.copy_mask(&s.c, &mut kept).unwrap();
    s.b.upload_mask(&mut s.c, &vec![true; NX * NY]).unwrap();
    s.b.copy_mask(&kept, &mut s.c).unwrap();
    let mut got = vec![false; NX * NY];
    s.b.download_mask(&s.c, &mut got).unwrap();
    assert!(
        got == s.mask,
        "the restored contact set differs from the saved one"
    );
}

/// y += sign·(num/den)·x on C (y unchanged off C, whatever x is there); a zero denominator
/// gives a zero step.
fn axpy_ratio<B: Backend>(mut s: Subject<B>) {
    let (x, y) = (pseudo_random(NX * NY, 6), pseudo_random(NX * NY, 8));
    let y = on_c(&y, &s.mask);
    let fx = s.put(&poisoned(&x, &s.mask));
    let mut fy = s.put(&y);
    let r = s.slots(3);
    let ones = s.put(&vec![1.0; NX * NY]);
    // num = Σ_C 1 = |C|, den = 2|C|: the ratio is exactly 1/2.
    s.b.dot(&s.c, &ones, &ones, r[0]).unwrap();
    s.b.dot(&s.c, &ones, &ones, r[1]).unwrap();
    let half = s.put(&vec![2.0f64.sqrt(); NX * NY]);
    s.b.dot(&s.c, &half, &half, r[1]).unwrap();
    s.b.axpy_ratio(&s.c, &mut fy, &fx, r[0], r[1], -1.0)
        .unwrap();
    let want: Vec<f64> = (0..NX * NY)
        .map(|i| if s.mask[i] { y[i] - 0.5 * x[i] } else { 0.0 })
        .collect();
    let got = s.get(&fy);
    s.assert_close("axpy_ratio", &got, &want);
    s.b.axpy_ratio(&s.c, &mut fy, &fx, r[0], r[2], 1.0).unwrap();
    let got = s.get(&fy);
    s.assert_close("axpy_ratio with 0 denominator", &got, &want);
}

/// y = x + (num/den)·y on C, 0 off C, with x and y NaN off C.
fn xpay_ratio<B: Backend>(mut s: Subject<B>) {
    let (x, y) = (pseudo_random(NX * NY, 9), pseudo_random(NX * NY, 10));
    let fx = s.put(&poisoned(&x, &s.mask));
    let mut fy = s.put(&poisoned(&y, &s.mask));
    let r = s.slots(3);
    let ones = s.put(&vec![1.0; NX * NY]);
    let two = s.put(&vec![2.0; NX * NY]);
    s.b.dot(&s.c, &ones, &ones, r[0]).unwrap();
    s.b.dot(&s.c, &two, &two, r[1]).unwrap();
    s.b.xpay_ratio(&s.c, &mut fy, &fx, r[0], r[1]).unwrap();
    let want: Vec<f64> = (0..NX * NY)
        .map(|i| if s.mask[i] { x[i] + 0.25 * y[i] } else { 0.0 })
        .collect();
    let got = s.get(&fy);
    s.assert_close("xpay_ratio", &got, &want);
    s.b.xpay_ratio(&s.c, &mut fy, &fx, r[0], r[2]).unwrap();
    let got = s.get(&fy);
    s.assert_close("xpay_ratio with 0 denominator", &got, &on_c(&x, &s.mask));
}

/// dst = a + t(b − a) on C, 0 off C, with a and b NaN off C and dst NaN before.
fn lerp<B: Backend>(mut s: Subject<B>) {
    let (a, b) = (pseudo_random(NX * NY, 11), pseudo_random(NX * NY, 12));
    let fa = s.put(&poisoned(&a, &s.mask));
    let fb = s.put(&poisoned(&b, &s.mask));
    let mut dst = s.put(&vec![f64::NAN; NX * NY]);
    s.b.lerp(&s.c, &fa, &fb, 0.3, &mut dst).unwrap();
    let want: Vec<f64> = (0..NX * NY)
        .map(|i| {
            if s.mask[i] {
                a[i] + 0.3 * (b[i] - a[i])
            } else {
                0.0
            }
        })
        .collect();
    let got = s.get(&dst);
    s.assert_close("lerp", &got, &want);
}

/// min over C of (−σ_c − p_old)/(p_new − p_old) where p_new < −σ_c, with both NaN off C.
fn first_crossing<B: Backend>(mut s: Subject<B>) {
    let sigma_c = 0.5;
    let old: Vec<f64> = pseudo_random(NX * NY, 13).iter().map(|v| 0.2 * v).collect();
    let new: Vec<f64> = pseudo_random(NX * NY, 14)
        .iter()
        .map(|v| 0.8 * v - 0.1)
        .collect();
    let fo = s.put(&poisoned(&old, &s.mask));
    let fn_ = s.put(&poisoned(&new, &s.mask));
    let got = s.b.first_crossing(&s.c, &fo, &fn_, sigma_c).unwrap();
    let want = (0..NX * NY)
        .filter(|&i| s.mask[i] && new[i] < -sigma_c)
        .map(|i| (-sigma_c - old[i]) / (new[i] - old[i]))
        .fold(1.0f64, f64::min);
    assert!(want < 1.0, "the inputs must cross somewhere");
    s.assert_scalar("first_crossing", got, want, 1.0);
}

/// max over C of |f|, with NaN off C ignored.
fn max_abs<B: Backend>(mut s: Subject<B>) {
    let v: Vec<f64> = pseudo_random(NX * NY, 19)
        .iter()
        .map(|x| 3.0 * x - 1.0)
        .collect();
    let f = s.put(&poisoned(&v, &s.mask));
    let got = s.b.max_abs(&s.c, &f).unwrap();
    let want = (0..NX * NY)
        .filter(|&i| s.mask[i])
        .map(|i| v[i].abs())
        .fold(0.0f64, f64::max);
    assert!(want > 0.0, "the inputs must be non-zero on C");
    s.assert_scalar("max_abs", got, want, want);
}

/// One Pohrt–Popov sweep: detach p < −σ_c on C, attach negative gaps off C, p = 0 off the
/// new C; counts, mask and p as the rule says.
fn update_contact<B: Backend>(s: Subject<B>) {
    sweep(s, Some(0.2));
}

/// A detach-only sweep (what an approximately solved cascade round makes): the same, but
/// nothing attaches whatever the gap.
fn update_contact_detach_only<B: Backend>(s: Subject<B>) {
    sweep(s, None);
}

fn sweep<B: Backend>(mut s: Subject<B>, attach_at: Option<f64>) {
    let h = setup().profile;
    let sigma_c = 0.6;
    let p = on_c(&pseudo_random(NX * NY, 15), &s.mask);
    let u: Vec<f64> = pseudo_random(NX * NY, 16).iter().map(|v| 0.5 * v).collect();
    let mut fp = s.put(&p);
    let fu = s.put(&u);
    let change =
        s.b.update_contact(&mut s.c, &mut fp, &fu, attach_at, sigma_c)
            .unwrap();
    let mut want_mask = s.mask.clone();
    let (mut detached, mut attached) = (0, 0);
    for i in 0..NX * NY {
        if s.mask[i] && p[i] < -sigma_c {
            want_mask[i] = false;
            detached += 1;
        } else if !s.mask[i] && attach_at.is_some_and(|d| h[i] - d + u[i] < 0.0) {
            want_mask[i] = true;
            attached += 1;
        }
    }
    assert!(detached > 0, "the inputs must detach some");
    if attach_at.is_some() {
        assert!(attached > 0, "the inputs must attach some");
    }
    assert_eq!((change.detached, change.attached), (detached, attached));
    assert_eq!(change.n_contact, want_mask.iter().filter(|m| **m).count());
    // The elements of C on the domain's outer ring; a periodic domain has no edge.
    let ring = (0..NX * NY)
        .filter(|&i| {
            let (x, y) = (i % NX, i / NX);
            want_mask[i] && (x == 0 || y == 0 || x == NX - 1 || y == NY - 1)
        })
        .count();
    assert!(ring > 0, "the inputs must leave contact at the edge");
    let want_edge = if periodic(&s.b) { 0 } else { ring };
    assert_eq!(change.at_edge, want_edge, "contact at the edge");
    let mut got_mask = vec![false; NX * NY];
    s.b.download_mask(&s.c, &mut got_mask).unwrap();
    assert_eq!(got_mask, want_mask, "the contact set after the sweep");
    let want_p: Vec<f64> = (0..NX * NY)
        .map(|i| if want_mask[i] && s.mask[i] { p[i] } else { 0.0 })
        .collect();
    let got = s.get(&fp);
    s.assert_close("p after the sweep", &got, &want_p);
}

/// A cascade round's predicted start: each element of C takes the shares of the load that
/// its neighbours off C held before the sweep (within the share radius, on the grid).
fn spread_detached<B: Backend>(mut s: Subject<B>) {
    use jkrbem::backend::shares::{detachment_shares, SHARE_RADIUS};
    // Before the sweep: a larger contact set (C plus about half of the rest), p on it.
    let extra: Vec<bool> = pseudo_random(NX * NY, 23)
        .iter()
        .map(|v| *v < 0.0)
        .collect();
    let old: Vec<bool> = (0..NX * NY).map(|i| s.mask[i] || extra[i]).collect();
    let before = on_c(&pseudo_random(NX * NY, 21), &old);
    let p = pseudo_random(NX * NY, 22);
    let fb = s.put(&before);
    let mut fp = s.put(&poisoned(&p, &s.mask));
    s.b.spread_detached(&s.c, &fb, &mut fp).unwrap();
    let (w, r) = (detachment_shares(), SHARE_RADIUS as i64);
    let want: Vec<f64> = (0..NX * NY)
        .map(|i| {
            if !s.mask[i] {
                return 0.0;
            }
            let (x, y) = ((i % NX) as i64, (i / NX) as i64);
            let mut v = p[i];
            for oy in -r..=r {
                for ox in -r..=r {
                    let (xx, yy) = (x + ox, y + oy);
                    if (0..NX as i64).contains(&xx) && (0..NY as i64).contains(&yy) {
                        let j = yy as usize * NX + xx as usize;
                        if !s.mask[j] {
                            v += w[((oy + r) * (2 * r + 1) + ox + r) as usize] * before[j];
                        }
                    }
                }
            }
            v
        })
        .collect();
    assert!(
        (0..NX * NY).any(|i| s.mask[i] && (want[i] - p[i]).abs() > 0.01),
        "the inputs must hand some load on"
    );
    let got = on_c(&s.get(&fp), &s.mask);
    s.assert_close("p after the spread", &got, &want);
}

/// Detachments certain before a solve: the backend's certification equals the host's
/// (`backend::certify::certify_detached`, the twin of shaders/certify.wgsl) on a band of
/// contact whose lower edge has partly just detached: the same elements certified, their p
/// zeroed, the candidates kept given the same predicted start. The periodic backend takes
/// none (its bound is the plane's). Twice on one backend: a long cascade of generations, then
/// a shorter one (a device that records several generations before it reads their counts
/// sizes its batch from the last one, so the second stops inside a batch).
fn certify_detached<B: Backend>(mut s: Subject<B>) {
    for detached in [10..=13, 6..=24] {
        if !certify_case(&mut s, detached) {
            return;
        }
    }
}

/// One case of [`certify_detached`]: the band's lower edge detached over `detached` (x);
/// false where the backend takes no certification (the periodic ones).
fn certify_case<B: Backend>(s: &mut Subject<B>, detached: std::ops::RangeInclusive<usize>) -> bool {
    let sigma_c = 1.0;
    let eps = 1e-3;
    // Before the sweep: the band 3 ≤ y ≤ 12 in contact, tensile, most so near its edges.
    let noise = pseudo_random(NX * NY, 31);
    let band = |i: usize| (3..=12).contains(&(i / NX));
    let before: Vec<f64> = (0..NX * NY)
        .map(|i| {
            if !band(i) {
                return 0.0;
            }
            let edge = (i / NX).abs_diff(3).min((i / NX).abs_diff(12)) as f64;
            (-0.92 + 0.4 * edge + 0.04 * noise[i]).min(-0.1)
        })
        .collect();
    // The sweep detached the lower edge's elements in `detached` (made over σ_c).
    let mut before = before;
    let swept: Vec<bool> = (0..NX * NY)
        .map(|i| {
            let detached = i / NX == 3 && detached.contains(&(i % NX));
            if detached {
                before[i] = -1.2 - 0.1 * noise[i].abs();
            }
            band(i) && !detached
        })
        .collect();
    let p = on_c(&before, &swept);
    s.b.upload_mask(&mut s.c, &swept).unwrap();
    let fb = s.put(&before);
    let mut fp = s.put(&p);
    let got =
        s.b.certify_detached(&mut s.c, &fb, &mut fp, sigma_c, eps)
            .unwrap();
    let mut got_mask = vec![false; NX * NY];
    s.b.download_mask(&s.c, &mut got_mask).unwrap();
    let got_p = s.get(&fp);
    if periodic(&s.b) {
        assert_eq!(got, None, "the periodic backend certified");
        assert_eq!(got_mask, swept);
        s.assert_close("p untouched", &got_p, &p);
        return false;
    }
    let (mut want_mask, mut want_p) = (swept.clone(), p.clone());
    let want = jkrbem::backend::certify::certify_detached(
        &mut want_mask,
        &before,
        &mut want_p,
        NX,
        NY,
        sigma_c,
        eps,
    );
    assert!(want.is_some_and(|n| n > 0), "the inputs must certify some");
    // Candidates kept too (within the candidates' reach of the rows removed): the bound
    // decides both ways.
    assert!(
        (4 * NX..8 * NX).any(|i| want_mask[i]),
        "the inputs must leave some candidates in contact"
    );
    assert_eq!(got, want, "elements certified");
    assert_eq!(
        got_mask, want_mask,
        "the contact set after the certification"
    );
    s.assert_close("p after the certification", &got_p, &want_p);
    true
}

/// The convolution is linear and symmetric (⟨a, Kb⟩ = ⟨Ka, b⟩) on every backend, and the
/// padded ones equal the padded CPU backend.
fn convolution<B: Backend>(mut s: Subject<B>) {
    let (a, b) = (pseudo_random(NX * NY, 17), pseudo_random(NX * NY, 18));
    let sum: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x + y).collect();
    let conv = |s: &mut Subject<B>, v: &[f64]| {
        let fv = s.put(v);
        let mut out = s.put(&vec![f64::NAN; NX * NY]);
        s.b.convolve(&fv, &mut out).unwrap();
        s.get(&out)
    };
    let (ka, kb, ks) = (conv(&mut s, &a), conv(&mut s, &b), conv(&mut s, &sum));
    let lin: Vec<f64> = ka.iter().zip(&kb).map(|(x, y)| x + y).collect();
    s.assert_close("K(a + b) = Ka + Kb", &ks, &lin);
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
    let scale: f64 = a.iter().zip(&kb).map(|(x, y)| (x * y).abs()).sum();
    s.assert_scalar("⟨a, Kb⟩ = ⟨Ka, b⟩", dot(&a, &kb), dot(&ka, &b), scale);
    let mut reference = cpu_twin(&s.b);
    let mut want = vec![0.0; NX * NY];
    reference.convolve(&a, &mut want).unwrap();
    s.assert_close("K a against the CPU backend's", &ka, &want);
    if periodic(&s.b) {
        // The periodic displacement has zero mean (q = 0 set to zero).
        let mean = ka.iter().sum::<f64>() / (NX * NY) as f64;
        let size = ka.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(mean.abs() <= 10.0 * s.tol * size, "mean {mean}");
    }
}

/// Whether `b` is a backend with the periodic convolution.
fn periodic<B: Backend>(b: &B) -> bool {
    b.name().ends_with("-periodic")
}

/// The CPU backend with `b`'s convolution (padded or periodic), for reference.
fn cpu_twin<B: Backend>(b: &B) -> CpuBackend {
    if periodic(b) {
        CpuBackend::new_periodic(&setup()).unwrap()
    } else {
        CpuBackend::new(&setup()).unwrap()
    }
}

/// The preconditioner of a residual (zero off C) is zero off C and equals the CPU one.
fn preconditioner<B: Backend>(mut s: Subject<B>) {
    let r = on_c(&pseudo_random(NX * NY, 19), &s.mask);
    let fr = s.put(&r);
    let mut z = s.put(&vec![f64::NAN; NX * NY]);
    s.b.precondition(&s.c, &fr, &mut z).unwrap();
    let mut reference = CpuBackend::new(&setup()).unwrap();
    let mut want = vec![0.0; NX * NY];
    reference.precondition(&s.mask, &r, &mut want).unwrap();
    assert!(want.iter().zip(&s.mask).all(|(v, m)| *m || *v == 0.0));
    let got = s.get(&z);
    s.assert_close("precondition", &got, &want);
}

/// The fused operations equal their parts, with q = Ks NaN off C (only C may be read).
fn fused<B: Backend>(mut s: Subject<B>) {
    let m = s.mask.clone();
    let src = on_c(&pseudo_random(NX * NY, 20), &m);
    let fs = s.put(&src);
    let r = s.slots(6);
    // convolve_dot: dst = K s, out = Σ_C s·Ks.
    let mut q = s.put(&vec![f64::NAN; NX * NY]);
    s.b.convolve_dot(&s.c, &fs, &mut q, r[0]).unwrap();
    let kq = s.get(&q);
    let mut reference = cpu_twin(&s.b);
    let mut want = vec![0.0; NX * NY];
    reference.convolve(&src, &mut want).unwrap();
    s.assert_close("convolve_dot's field", &kq, &want);
    let dot = |x: &[f64], y: &[f64]| -> (f64, f64) {
        let terms = x.iter().zip(y).zip(&m).filter(|(_, m)| **m);
        let t: Vec<f64> = terms.map(|((a, b), _)| a * b).collect();
        (t.iter().sum(), t.iter().map(|v| v.abs()).sum())
    };
    let (want_sq, scale) = dot(&src, &kq);
    let got = s.read(r[0]);
    s.assert_scalar("convolve_dot's s·Ks", got, want_sq, scale);
    // precondition_dot: z = M s, out = Σ_C s·z.
    let mut z = s.put(&vec![f64::NAN; NX * NY]);
    s.b.precondition_dot(&s.c, &fs, &mut z, r[1]).unwrap();
    let zs = s.get(&z);
    let (want_rz, scale) = dot(&src, &zs);
    let got = s.read(r[1]);
    s.assert_scalar("precondition_dot's r·z", got, want_rz, scale);
    // cg_update with α = r[1]/r[0]: x += α s, r −= α q on C; rr = Σ_C r·r. q is NaN off C.
    let (x0, r0) = (
        on_c(&pseudo_random(NX * NY, 21), &m),
        poisoned(&pseudo_random(NX * NY, 22), &m),
    );
    let mut fx = s.put(&x0);
    let mut fr = s.put(&r0);
    let fq = s.put(&poisoned(&kq, &m));
    s.b.cg_update(&s.c, &mut fx, &mut fr, &fs, &fq, r[1], r[0], r[2])
        .unwrap();
    let alpha = want_rz / want_sq;
    let want_x: Vec<f64> = (0..NX * NY)
        .map(|i| if m[i] { x0[i] + alpha * src[i] } else { 0.0 })
        .collect();
    let got = s.get(&fx);
    s.assert_close("cg_update's x", &got, &want_x);
    let want_r: Vec<f64> = (0..NX * NY)
        .map(|i| if m[i] { r0[i] - alpha * kq[i] } else { 0.0 })
        .collect();
    let got_r = on_c(&s.get(&fr), &m);
    s.assert_close("cg_update's r on C", &got_r, &want_r);
    let (want_rr, scale) = dot(&want_r, &want_r);
    let got = s.read(r[2]);
    s.assert_scalar("cg_update's r·r", got, want_rr, scale);
}

/// Under a guard whose tolerance any residual meets, a device that queues CG steps stops
/// them itself after the first: the second iteration changes nothing, and the progress read
/// says one step was made. A backend without a guard makes every step and says nothing.
fn guard<B: Backend>(mut s: Subject<B>) {
    let m = s.mask.clone();
    let r0 = on_c(&pseudo_random(NX * NY, 23), &m);
    let r = s.slots(5);
    let (sq, rz, rz_new, rr, bb) = (r[0], r[1], r[2], r[3], r[4]);
    let mut fr = s.put(&r0);
    let mut fx = s.put(&vec![0.0; NX * NY]);
    let mut fs = s.put(&vec![0.0; NX * NY]);
    let mut z = s.put(&vec![0.0; NX * NY]);
    let mut q = s.put(&vec![0.0; NX * NY]);
    s.b.dot(&s.c, &fr, &fr, bb).unwrap();
    // CG's start: z = M r, s = z.
    s.b.precondition_dot(&s.c, &fr, &mut z, rz).unwrap();
    s.b.copy(&z, &mut fs).unwrap();
    s.b.guard_cg(Some(CgStop {
        rr,
        bb,
        tolerance: 1e30,
    }))
    .unwrap();
    let mut after_first = Vec::new();
    for step in 0..2 {
        s.b.convolve_dot(&s.c, &fs, &mut q, sq).unwrap();
        s.b.cg_update(&s.c, &mut fx, &mut fr, &fs, &q, rz, sq, rr)
            .unwrap();
        s.b.precondition_dot(&s.c, &fr, &mut z, rz_new).unwrap();
        s.b.xpay_ratio(&s.c, &mut fs, &z, rz_new, rz).unwrap();
        s.b.copy_slot(rz_new, rz).unwrap();
        if step == 0 {
            after_first = s.get(&fx);
        }
    }
    let steps = s.b.read_cg_status(&[rr], &mut [0.0]).unwrap();
    s.b.guard_cg(None).unwrap();
    let x = s.get(&fx);
    match steps {
        Some(n) => {
            assert_eq!(n, 1, "one step made, the second stopped on the device");
            s.assert_close("x after the stopped step", &x, &after_first);
        }
        None => {
            assert_eq!(
                s.b.check_every(),
                1,
                "a backend without a guard reads every step"
            );
            assert!(
                x.iter().zip(&after_first).any(|(a, b)| a != b),
                "both steps made"
            );
        }
    }
}

/// The checks, by name.
type Check<B> = fn(Subject<B>);

fn checks<B: Backend + 'static>() -> Vec<(&'static str, Check<B>)> {
    vec![
        ("fields_and_copy", fields_and_copy::<B>),
        ("slots", slots::<B>),
        ("residual", residual::<B>),
        ("reductions", reductions::<B>),
        ("measure", measure::<B>),
        ("save_and_restore_contact", save_and_restore_contact::<B>),
        ("axpy_ratio", axpy_ratio::<B>),
        ("xpay_ratio", xpay_ratio::<B>),
        ("lerp", lerp::<B>),
        ("first_crossing", first_crossing::<B>),
        ("max_abs", max_abs::<B>),
        ("update_contact", update_contact::<B>),
        (
            "update_contact_detach_only",
            update_contact_detach_only::<B>,
        ),
        ("spread_detached", spread_detached::<B>),
        ("certify_detached", certify_detached::<B>),
        ("convolution", convolution::<B>),
        ("preconditioner", preconditioner::<B>),
        ("fused", fused::<B>),
        ("guard", guard::<B>),
    ]
}

/// Trials of every check on the backend that `open` builds; ignored with `skip` as the reason.
fn trials<B: Backend + 'static>(
    name: &'static str,
    open: fn() -> B,
    skip: Option<&str>,
) -> Vec<Trial> {
    checks::<B>()
        .into_iter()
        .map(|(check, f)| {
            let t = Trial::test(format!("conformance::{name}::{check}"), move || {
                common::in_process(false, || f(Subject::new(open())));
                Ok(())
            });
            match skip {
                Some(reason) => t.with_ignored_flag(true).with_kind(reason.to_string()),
                None => t,
            }
        })
        .collect()
}

/// The checks on every backend, for `tests/gpu/main.rs`; `gpu_missing`: why there is no GPU
/// adapter (the gpu checks are then reported as ignored with it).
#[cfg_attr(not(feature = "gpu"), allow(unused_variables))]
pub fn all(gpu_missing: Option<&'static str>) -> Vec<Trial> {
    let mut all = trials("cpu", || CpuBackend::new(&setup()).unwrap(), None);
    all.extend(trials(
        "cpu-periodic",
        || CpuBackend::new_periodic(&setup()).unwrap(),
        None,
    ));
    #[cfg(feature = "gpu")]
    {
        use jkrbem::backend::gpu::{GpuBackend, GpuContext};
        all.extend(trials(
            "gpu",
            || {
                let ctx = GpuContext::new(Default::default()).expect("a GPU adapter");
                GpuBackend::new(ctx, &setup()).expect("the GPU backend opens")
            },
            gpu_missing,
        ));
        all.extend(trials(
            "gpu-periodic",
            || {
                let ctx = GpuContext::new(Default::default()).expect("a GPU adapter");
                GpuBackend::new_periodic(ctx, &setup()).expect("the periodic GPU backend opens")
            },
            gpu_missing,
        ));
    }
    all
}
