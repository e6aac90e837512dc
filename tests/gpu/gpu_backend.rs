//! Every operation of the GPU backend (the WGSL kernels of shaders/) against its CPU twin,
//! the f64 CPU backend, on the same inputs: the padded convolution and the preconditioner on
//! square and rectangular grids, the masked CG vector updates, the reductions against f64
//! sums, the contact sweep and the first crossing.
//!
//! Skips with a message when no GPU adapter exists, unless `JKRBEM_REQUIRE_GPU=1`.

use crate::common;

use common::{gpu_backend, pseudo_random};
use jkrbem::backend::gpu::GpuBackend;
use jkrbem::backend::prelude::*;
use jkrbem::backend::{cpu::CpuBackend, GridSetup};
use jkrbem::backend::{ChordAxes, Preconditioner, Slot};

fn setup(nx: usize, ny: usize, preconditioner: Preconditioner) -> GridSetup {
    GridSetup {
        nx,
        ny,
        dx: 0.05,
        e_star: 1.7,
        profile: pseudo_random(nx * ny, 99).iter().map(|v| 0.3 + v).collect(),
        preconditioner,
    }
}

fn pair(nx: usize, ny: usize, pre: Preconditioner) -> Option<(CpuBackend, GpuBackend)> {
    let s = setup(nx, ny, pre);
    let gpu = gpu_backend(&s)?;
    Some((CpuBackend::new(&s).unwrap(), gpu))
}

/// A mask with about `fraction` of the elements in contact.
fn mask(n: usize, seed: u64, fraction: f64) -> Vec<bool> {
    pseudo_random(n, seed)
        .iter()
        .map(|v| (v + 1.0) / 2.0 < fraction)
        .collect()
}

/// Upload the same host values to both backends.
fn fields(
    cpu: &mut CpuBackend,
    gpu: &mut GpuBackend,
    host: &[f64],
) -> (Vec<f64>, jkrbem::backend::gpu::GpuField) {
    let mut c = cpu.field().unwrap();
    cpu.upload(&mut c, host).unwrap();
    let mut g = gpu.field().unwrap();
    gpu.upload(&mut g, host).unwrap();
    (c, g)
}

fn download(gpu: &mut GpuBackend, f: &jkrbem::backend::gpu::GpuField) -> Vec<f64> {
    let (nx, ny) = gpu.shape();
    let mut out = vec![0.0; nx * ny];
    gpu.download(f, &mut out).unwrap();
    out
}

/// max |a − b| / max |b|.
fn relative(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

fn convolution_matches_cpu_on_square_and_rectangular_grids() {
    // (16, 2048) pads to 32 × 4096: the column FFTs need global-memory stages.
    for (nx, ny) in [
        (16, 16),
        (32, 16),
        (16, 64),
        (128, 64),
        (256, 256),
        (16, 2048),
    ] {
        let Some((mut cpu, mut gpu)) = pair(nx, ny, Preconditioner::None) else {
            return;
        };
        let p = pseudo_random(nx * ny, (nx * 31 + ny) as u64);
        let (cp, gp) = fields(&mut cpu, &mut gpu, &p);
        let (mut cu, mut gu) = (cpu.field().unwrap(), gpu.field().unwrap());
        cpu.convolve(&cp, &mut cu).unwrap();
        gpu.convolve(&gp, &mut gu).unwrap();
        let err = relative(&download(&mut gpu, &gu), &cu);
        println!("convolution {nx}×{ny}: max relative difference GPU (f32) vs CPU (f64) {err:.2e}");
        assert!(err < 2e-6, "{nx}×{ny}: {err:e}");
    }
}

fn preconditioner_matches_cpu_with_a_mask() {
    for (nx, ny) in [(16, 16), (64, 32), (32, 128)] {
        let Some((mut cpu, mut gpu)) = pair(nx, ny, Preconditioner::Stiffness) else {
            return;
        };
        let m = mask(nx * ny, 5, 0.6);
        let mut cpu_c = cpu.mask().unwrap();
        cpu.upload_mask(&mut cpu_c, &m).unwrap();
        let mut gpu_c = gpu.mask().unwrap();
        gpu.upload_mask(&mut gpu_c, &m).unwrap();
        let r = pseudo_random(nx * ny, 11);
        let (cr, gr) = fields(&mut cpu, &mut gpu, &r);
        let (mut cz, mut gz) = (cpu.field().unwrap(), gpu.field().unwrap());
        cpu.precondition(&cpu_c, &cr, &mut cz).unwrap();
        gpu.precondition(&gpu_c, &gr, &mut gz).unwrap();
        let gz = download(&mut gpu, &gz);
        let err = relative(&gz, &cz);
        println!("preconditioner {nx}×{ny}: max relative difference {err:.2e}");
        assert!(err < 2e-6, "{nx}×{ny}: {err:e}");
        assert!(gz.iter().zip(&m).all(|(v, &on)| on || *v == 0.0));
    }
}

fn cg_vector_operations_match_cpu() {
    let (nx, ny) = (64, 32);
    let Some((mut cpu, mut gpu)) = pair(nx, ny, Preconditioner::None) else {
        return;
    };
    // Eight registers on each backend; the last is never written, so it stays 0.
    let cs: Vec<Slot> = (0..8).map(|_| cpu.slot().unwrap()).collect();
    let gs: Vec<Slot> = (0..8).map(|_| gpu.slot().unwrap()).collect();
    let n = nx * ny;
    let m = mask(n, 7, 0.5);
    let mut cpu_c = cpu.mask().unwrap();
    cpu.upload_mask(&mut cpu_c, &m).unwrap();
    let mut gpu_c = gpu.mask().unwrap();
    gpu.upload_mask(&mut gpu_c, &m).unwrap();
    let (ca, ga) = fields(&mut cpu, &mut gpu, &pseudo_random(n, 1));
    let (cb, gb) = fields(&mut cpu, &mut gpu, &pseudo_random(n, 2));
    let (mut cy, mut gy) = fields(&mut cpu, &mut gpu, &pseudo_random(n, 3));
    let check = |what: &str, g: Vec<f64>, c: &[f64]| {
        let err = relative(&g, c);
        println!("{what}: max relative difference {err:.2e}");
        assert!(err < 1e-6, "{what}: {err:e}");
    };

    cpu.residual(&cpu_c, &ca, 0.7, &mut cy).unwrap();
    gpu.residual(&gpu_c, &ga, 0.7, &mut gy).unwrap();
    check("residual", download(&mut gpu, &gy), &cy);

    // Slots 0 = a·b, 1 = a·a: ratios computed on the device.
    cpu.dot(&cpu_c, &ca, &cb, cs[0]).unwrap();
    cpu.dot(&cpu_c, &ca, &ca, cs[1]).unwrap();
    gpu.dot(&gpu_c, &ga, &gb, gs[0]).unwrap();
    gpu.dot(&gpu_c, &ga, &ga, gs[1]).unwrap();
    cpu.axpy_ratio(&cpu_c, &mut cy, &cb, cs[0], cs[1], -1.0)
        .unwrap();
    gpu.axpy_ratio(&gpu_c, &mut gy, &gb, gs[0], gs[1], -1.0)
        .unwrap();
    check("axpy_ratio", download(&mut gpu, &gy), &cy);
    cpu.xpay_ratio(&cpu_c, &mut cy, &ca, cs[1], cs[0]).unwrap();
    gpu.xpay_ratio(&gpu_c, &mut gy, &ga, gs[1], gs[0]).unwrap();
    check("xpay_ratio", download(&mut gpu, &gy), &cy);
    // A zero denominator gives a zero step: y = x.
    cpu.xpay_ratio(&cpu_c, &mut cy, &cb, cs[0], cs[7]).unwrap();
    gpu.xpay_ratio(&gpu_c, &mut gy, &gb, gs[0], gs[7]).unwrap();
    check("xpay_ratio 0/0", download(&mut gpu, &gy), &cy);
    cpu.copy_slot(cs[0], cs[5]).unwrap();
    gpu.copy_slot(gs[0], gs[5]).unwrap();
    let (mut c5, mut g5) = ([0.0; 2], [0.0; 2]);
    cpu.read_slots(&[cs[5], cs[1]], &mut c5).unwrap();
    gpu.read_slots(&[gs[5], gs[1]], &mut g5).unwrap();
    for (g, c) in g5.iter().zip(c5) {
        assert!((g - c).abs() <= 1e-6 * c.abs(), "slots {g5:?} vs {c5:?}");
    }
    cpu.lerp(&cpu_c, &ca, &cb, 0.3, &mut cy).unwrap();
    gpu.lerp(&gpu_c, &ga, &gb, 0.3, &mut gy).unwrap();
    check("lerp", download(&mut gpu, &gy), &cy);
    cpu.copy(&cb, &mut cy).unwrap();
    gpu.copy(&gb, &mut gy).unwrap();
    check("copy", download(&mut gpu, &gy), &cy);
    let cm = cpu.measure(&cpu_c, &ca, ChordAxes::ALIGNED).unwrap();
    let gm = gpu.measure(&gpu_c, &ga, ChordAxes::ALIGNED).unwrap();
    assert_eq!(
        (gm.count, gm.half_lengths, gm.bounds),
        (cm.count, cm.half_lengths, cm.bounds)
    );
    assert!((gm.sum - cm.sum).abs() <= 1e-5 * ca.iter().map(|v| v.abs()).sum::<f64>());
}

fn reductions_match_f64_sums_on_a_large_grid() {
    let (nx, ny) = (1024, 512);
    let Some((mut cpu, mut gpu)) = pair(nx, ny, Preconditioner::None) else {
        return;
    };
    // Eight registers on each backend; the last is never written, so it stays 0.
    let cs: Vec<Slot> = (0..8).map(|_| cpu.slot().unwrap()).collect();
    let gs: Vec<Slot> = (0..8).map(|_| gpu.slot().unwrap()).collect();
    let n = nx * ny;
    let m = mask(n, 13, 0.8);
    let mut cpu_c = cpu.mask().unwrap();
    cpu.upload_mask(&mut cpu_c, &m).unwrap();
    let mut gpu_c = gpu.mask().unwrap();
    gpu.upload_mask(&mut gpu_c, &m).unwrap();
    // Positive values: the worst case for a running f32 sum (it keeps growing).
    let a: Vec<f64> = pseudo_random(n, 17).iter().map(|v| 1.0 + 0.5 * v).collect();
    let b: Vec<f64> = pseudo_random(n, 19).iter().map(|v| 2.0 + v).collect();
    let (ca, ga) = fields(&mut cpu, &mut gpu, &a);
    let (cb, gb) = fields(&mut cpu, &mut gpu, &b);
    // The f64 sum of the f32-rounded inputs isolates the reduction's own error.
    let exact: f64 = a
        .iter()
        .zip(&b)
        .zip(&m)
        .filter(|(_, &on)| on)
        .map(|((x, y), _)| (*x as f32 as f64) * (*y as f32 as f64))
        .sum();
    gpu.dot(&gpu_c, &ga, &gb, gs[2]).unwrap();
    cpu.dot(&cpu_c, &ca, &cb, cs[2]).unwrap();
    let mut g = [0.0];
    gpu.read_slots(&[gs[2]], &mut g).unwrap();
    let naive = a
        .iter()
        .zip(&b)
        .zip(&m)
        .filter(|(_, &on)| on)
        .fold(0.0f32, |s, ((x, y), _)| s + (*x as f32) * (*y as f32));
    let err = (g[0] - exact).abs() / exact;
    let naive_err = (naive as f64 - exact).abs() / exact;
    println!(
        "dot over {} elements: GPU tree relative error {err:.2e}, a running f32 sum {naive_err:.2e}",
        m.iter().filter(|&&v| v).count()
    );
    assert!(err < 1e-6, "{err:e}");
}

fn contact_sweep_and_first_crossing_match_cpu() {
    let (nx, ny) = (64, 64);
    let Some((mut cpu, mut gpu)) = pair(nx, ny, Preconditioner::None) else {
        return;
    };
    let n = nx * ny;
    // A ring of contact away from the edge plus some elements on it.
    let mut m = mask(n, 23, 0.5);
    m[5] = true;
    let mut cpu_c = cpu.mask().unwrap();
    cpu.upload_mask(&mut cpu_c, &m).unwrap();
    let mut gpu_c = gpu.mask().unwrap();
    gpu.upload_mask(&mut gpu_c, &m).unwrap();
    let p_old: Vec<f64> = pseudo_random(n, 29).iter().map(|v| 0.5 * v).collect();
    let p_new: Vec<f64> = pseudo_random(n, 31).iter().map(|v| 2.0 * v).collect();
    let (c_old, g_old) = fields(&mut cpu, &mut gpu, &p_old);
    let (mut c_new, mut g_new) = fields(&mut cpu, &mut gpu, &p_new);
    let sigma = 0.6;
    let tc = cpu.first_crossing(&cpu_c, &c_old, &c_new, sigma).unwrap();
    let tg = gpu.first_crossing(&gpu_c, &g_old, &g_new, sigma).unwrap();
    println!("first crossing: CPU {tc:.7}, GPU {tg:.7}");
    assert!((tc - tg).abs() < 1e-6);
    let u: Vec<f64> = pseudo_random(n, 37).iter().map(|v| 0.2 * v).collect();
    let (cu, gu) = fields(&mut cpu, &mut gpu, &u);
    let cc = cpu
        .update_contact(&mut cpu_c, &mut c_new, &cu, Some(0.35), sigma)
        .unwrap();
    let gc = gpu
        .update_contact(&mut gpu_c, &mut g_new, &gu, Some(0.35), sigma)
        .unwrap();
    println!("contact sweep: CPU {cc:?}, GPU {gc:?}");
    assert_eq!(gc, cc);
    assert!(cc.detached > 0 && cc.attached > 0 && cc.at_edge > 0);
    let (mut cm, mut gm) = (vec![false; n], vec![false; n]);
    cpu.download_mask(&cpu_c, &mut cm).unwrap();
    gpu.download_mask(&gpu_c, &mut gm).unwrap();
    assert_eq!(gm, cm);
    assert_eq!(
        download(&mut gpu, &g_new),
        c_new.iter().map(|&v| v as f32 as f64).collect::<Vec<_>>()
    );
}

/// Resident memory of this process (KiB), from /proc (Linux).
fn resident_kib() -> Option<u64> {
    let statm = std::fs::read_to_string("/proc/self/statm").ok()?;
    Some(statm.split_whitespace().nth(1)?.parse::<u64>().ok()? * 4)
}

/// Before the fix, Mesa's lavapipe compiled a new variant of `rows_forward` at every dispatch,
/// inlining its uniform parameters, and never freed it: 0.7 MB per convolution at 64², 17 GB
/// over the pull-off tests. A thousand convolutions must leave memory where it was.
fn slow_repeated_convolutions_do_not_grow_memory() {
    let Some((_, mut gpu)) = pair(64, 64, Preconditioner::Stiffness) else {
        return;
    };
    let Some(before) = resident_kib() else {
        println!("no /proc/self/statm: memory not checked");
        return;
    };
    let a = gpu.field().unwrap();
    let mut b = gpu.field().unwrap();
    let mut gpu_c = gpu.mask().unwrap();
    gpu.upload_mask(&mut gpu_c, &vec![true; 64 * 64]).unwrap();
    let slot = gpu.slot().unwrap();
    let mut v = [0.0];
    // Warm-up: pipelines, caches and the allocator settle.
    for _ in 0..100 {
        gpu.convolve(&a, &mut b).unwrap();
        gpu.precondition(&gpu_c, &a, &mut b).unwrap();
        gpu.read_slots(&[slot], &mut v).unwrap();
    }
    let settled = resident_kib().unwrap();
    for _ in 0..1000 {
        gpu.convolve(&a, &mut b).unwrap();
        gpu.precondition(&gpu_c, &a, &mut b).unwrap();
        gpu.read_slots(&[slot], &mut v).unwrap();
    }
    let after = resident_kib().unwrap();
    println!(
        "resident memory: {before} KiB at the start, {settled} after 100 convolutions, {after} \
         after 1000 more"
    );
    assert!(
        after.saturating_sub(settled) < 64 * 1024,
        "1000 convolutions grew memory by {} KiB",
        after - settled
    );
}

/// This file's tests, for `tests/gpu/main.rs`; `missing`: why there is no GPU adapter.
pub fn trials(missing: Option<&str>) -> Vec<libtest_mimic::Trial> {
    common::gpu_trials(
        "gpu_backend",
        &[
            (
                "convolution_matches_cpu_on_square_and_rectangular_grids",
                convolution_matches_cpu_on_square_and_rectangular_grids,
            ),
            (
                "preconditioner_matches_cpu_with_a_mask",
                preconditioner_matches_cpu_with_a_mask,
            ),
            (
                "cg_vector_operations_match_cpu",
                cg_vector_operations_match_cpu,
            ),
            (
                "reductions_match_f64_sums_on_a_large_grid",
                reductions_match_f64_sums_on_a_large_grid,
            ),
            (
                "contact_sweep_and_first_crossing_match_cpu",
                contact_sweep_and_first_crossing_match_cpu,
            ),
            (
                "slow_repeated_convolutions_do_not_grow_memory",
                slow_repeated_convolutions_do_not_grow_memory,
            ),
        ],
        &[],
        &["slow_repeated_convolutions_do_not_grow_memory"],
        missing,
    )
}
