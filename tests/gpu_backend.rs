//! Every operation of the GPU backend (the WGSL kernels of shaders/) against its CPU twin,
//! the f64 CPU backend, on the same inputs: the padded convolution and the preconditioner on
//! square and rectangular grids, the masked CG vector updates, the reductions against f64
//! sums, the contact sweep and the first crossing.
//!
//! Skips with a message when no GPU adapter exists, unless `JKRBEM_REQUIRE_GPU=1`.

mod common;

use common::{gpu_backend, pseudo_random};
use jkrbem::backend::cpu::{CpuBackend, GridSetup};
use jkrbem::backend::gpu::GpuBackend;
use jkrbem::backend::{Backend, Preconditioner, Slot};

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

#[test]
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

#[test]
fn preconditioner_matches_cpu_with_a_mask() {
    for (nx, ny) in [(16, 16), (64, 32), (32, 128)] {
        let Some((mut cpu, mut gpu)) = pair(nx, ny, Preconditioner::Stiffness) else {
            return;
        };
        let m = mask(nx * ny, 5, 0.6);
        cpu.set_contact(&m).unwrap();
        gpu.set_contact(&m).unwrap();
        let r = pseudo_random(nx * ny, 11);
        let (cr, gr) = fields(&mut cpu, &mut gpu, &r);
        let (mut cz, mut gz) = (cpu.field().unwrap(), gpu.field().unwrap());
        cpu.precondition(&cr, &mut cz).unwrap();
        gpu.precondition(&gr, &mut gz).unwrap();
        let gz = download(&mut gpu, &gz);
        let err = relative(&gz, &cz);
        println!("preconditioner {nx}×{ny}: max relative difference {err:.2e}");
        assert!(err < 2e-6, "{nx}×{ny}: {err:e}");
        assert!(gz.iter().zip(&m).all(|(v, &on)| on || *v == 0.0));
    }
}

#[test]
fn cg_vector_operations_match_cpu() {
    let (nx, ny) = (64, 32);
    let Some((mut cpu, mut gpu)) = pair(nx, ny, Preconditioner::None) else {
        return;
    };
    let n = nx * ny;
    let m = mask(n, 7, 0.5);
    cpu.set_contact(&m).unwrap();
    gpu.set_contact(&m).unwrap();
    let (ca, ga) = fields(&mut cpu, &mut gpu, &pseudo_random(n, 1));
    let (cb, gb) = fields(&mut cpu, &mut gpu, &pseudo_random(n, 2));
    let (mut cy, mut gy) = fields(&mut cpu, &mut gpu, &pseudo_random(n, 3));
    let check = |what: &str, g: Vec<f64>, c: &[f64]| {
        let err = relative(&g, c);
        println!("{what}: max relative difference {err:.2e}");
        assert!(err < 1e-6, "{what}: {err:e}");
    };

    cpu.residual(&ca, 0.7, &mut cy).unwrap();
    gpu.residual(&ga, 0.7, &mut gy).unwrap();
    check("residual", download(&mut gpu, &gy), &cy);

    // Slots 0 = a·b, 1 = a·a: ratios computed on the device.
    cpu.dot(&ca, &cb, Slot(0)).unwrap();
    cpu.dot(&ca, &ca, Slot(1)).unwrap();
    gpu.dot(&ga, &gb, Slot(0)).unwrap();
    gpu.dot(&ga, &ga, Slot(1)).unwrap();
    cpu.axpy_ratio(&mut cy, &cb, Slot(0), Slot(1), -1.0)
        .unwrap();
    gpu.axpy_ratio(&mut gy, &gb, Slot(0), Slot(1), -1.0)
        .unwrap();
    check("axpy_ratio", download(&mut gpu, &gy), &cy);
    cpu.xpay_ratio(&mut cy, &ca, Slot(1), Slot(0)).unwrap();
    gpu.xpay_ratio(&mut gy, &ga, Slot(1), Slot(0)).unwrap();
    check("xpay_ratio", download(&mut gpu, &gy), &cy);
    // A zero denominator gives a zero step: y = x.
    cpu.xpay_ratio(&mut cy, &cb, Slot(0), Slot(7)).unwrap();
    gpu.xpay_ratio(&mut gy, &gb, Slot(0), Slot(7)).unwrap();
    check("xpay_ratio 0/0", download(&mut gpu, &gy), &cy);
    cpu.copy_slot(Slot(0), Slot(5)).unwrap();
    gpu.copy_slot(Slot(0), Slot(5)).unwrap();
    let (mut c5, mut g5) = ([0.0; 2], [0.0; 2]);
    cpu.read_slots(&[Slot(5), Slot(1)], &mut c5).unwrap();
    gpu.read_slots(&[Slot(5), Slot(1)], &mut g5).unwrap();
    for (g, c) in g5.iter().zip(c5) {
        assert!((g - c).abs() <= 1e-6 * c.abs(), "slots {g5:?} vs {c5:?}");
    }
    cpu.lerp(&ca, &cb, 0.3, &mut cy).unwrap();
    gpu.lerp(&ga, &gb, 0.3, &mut gy).unwrap();
    check("lerp", download(&mut gpu, &gy), &cy);
    cpu.copy(&cb, &mut cy).unwrap();
    gpu.copy(&gb, &mut gy).unwrap();
    check("copy", download(&mut gpu, &gy), &cy);
    let (cs, cn) = cpu.sum_and_count(&ca).unwrap();
    let (gs, gn) = gpu.sum_and_count(&ga).unwrap();
    assert_eq!(gn, cn);
    assert!((gs - cs).abs() <= 1e-5 * ca.iter().map(|v| v.abs()).sum::<f64>());
}

#[test]
fn reductions_match_f64_sums_on_a_large_grid() {
    let (nx, ny) = (1024, 512);
    let Some((mut cpu, mut gpu)) = pair(nx, ny, Preconditioner::None) else {
        return;
    };
    let n = nx * ny;
    let m = mask(n, 13, 0.8);
    cpu.set_contact(&m).unwrap();
    gpu.set_contact(&m).unwrap();
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
    gpu.dot(&ga, &gb, Slot(2)).unwrap();
    cpu.dot(&ca, &cb, Slot(2)).unwrap();
    let mut g = [0.0];
    gpu.read_slots(&[Slot(2)], &mut g).unwrap();
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

#[test]
fn contact_sweep_and_first_crossing_match_cpu() {
    let (nx, ny) = (64, 64);
    let Some((mut cpu, mut gpu)) = pair(nx, ny, Preconditioner::None) else {
        return;
    };
    let n = nx * ny;
    // A ring of contact away from the edge plus some elements on it.
    let mut m = mask(n, 23, 0.5);
    m[5] = true;
    cpu.set_contact(&m).unwrap();
    gpu.set_contact(&m).unwrap();
    let p_old: Vec<f64> = pseudo_random(n, 29).iter().map(|v| 0.5 * v).collect();
    let p_new: Vec<f64> = pseudo_random(n, 31).iter().map(|v| 2.0 * v).collect();
    let (c_old, g_old) = fields(&mut cpu, &mut gpu, &p_old);
    let (mut c_new, mut g_new) = fields(&mut cpu, &mut gpu, &p_new);
    let sigma = 0.6;
    let tc = cpu.first_crossing(&c_old, &c_new, sigma).unwrap();
    let tg = gpu.first_crossing(&g_old, &g_new, sigma).unwrap();
    println!("first crossing: CPU {tc:.7}, GPU {tg:.7}");
    assert!((tc - tg).abs() < 1e-6);
    let u: Vec<f64> = pseudo_random(n, 37).iter().map(|v| 0.2 * v).collect();
    let (cu, gu) = fields(&mut cpu, &mut gpu, &u);
    let cc = cpu.update_contact(&mut c_new, &cu, 0.35, sigma).unwrap();
    let gc = gpu.update_contact(&mut g_new, &gu, 0.35, sigma).unwrap();
    println!("contact sweep: CPU {cc:?}, GPU {gc:?}");
    assert_eq!(gc, cc);
    assert!(cc.detached > 0 && cc.attached > 0 && cc.at_edge > 0);
    let (mut cm, mut gm) = (vec![false; n], vec![false; n]);
    cpu.contact(&mut cm).unwrap();
    gpu.contact(&mut gm).unwrap();
    assert_eq!(gm, cm);
    assert_eq!(
        download(&mut gpu, &g_new),
        c_new.iter().map(|&v| v as f32 as f64).collect::<Vec<_>>()
    );
}
