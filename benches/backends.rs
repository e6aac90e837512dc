//! Criterion bench of one padded convolution on each backend, in the same run: the CPU
//! (rustfft, f64) and, where wgpu finds an adapter, the GPU (WGSL, f32). Each GPU sample ends
//! with one scalar readback so that it times finished work.
//!
//!     cargo bench --bench backends             # grids 64, 128, 256
//!     JKRBEM_BENCH_GRIDS=256,512,1024,2048 cargo bench --bench backends

use criterion::{BenchmarkId, Criterion};
use jkrbem::backend::cpu::CpuBackend;
use jkrbem::backend::gpu::{AdapterPreference, GpuBackend, GpuContext};
use jkrbem::backend::Backend;
use jkrbem::model::{Model, ModelOptions};
use jkrbem::scene::Scene;

fn model(n: usize) -> Model {
    let scene = Scene::from_ratio(1.0, 1.0, 1.0, 1.0).expect("a sphere is a valid scene");
    Model::build(
        &scene,
        &ModelOptions {
            nx: n,
            ..ModelOptions::default()
        },
    )
    .expect("a power-of-two grid is a valid model")
}

/// Benchmark `backend.convolve` on a Hertz-like pressure, ending with a scalar readback.
fn convolution<B: Backend>(c: &mut Criterion, backend: &mut B, model: &Model) {
    let mut p = backend.field().expect("field");
    let mut u = backend.field().expect("field");
    backend
        .upload(&mut p, &jkrbem::bench::hertz_like_pressure(model))
        .expect("upload");
    let mut contact = backend.mask().expect("mask");
    backend
        .upload_mask(&mut contact, &model.initial_contact())
        .expect("contact");
    let name = format!("convolution/{}-{}", backend.name(), backend.precision());
    let mut out = [0.0];
    let sync = backend.slot().expect("a register");
    c.bench_with_input(BenchmarkId::new(name, model.nx), &model.nx, |b, _| {
        b.iter(|| {
            backend.convolve(&p, &mut u).expect("convolve");
            backend.dot(&contact, &u, &u, sync).expect("dot");
            backend.read_slots(&[sync], &mut out).expect("read");
        })
    });
}

fn main() {
    let grids: Vec<usize> = std::env::var("JKRBEM_BENCH_GRIDS")
        .ok()
        .map(|s| s.split(',').filter_map(|g| g.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![64, 128, 256]);
    let mut c = Criterion::default().configure_from_args().sample_size(10);
    for &n in &grids {
        let m = model(n);
        let setup = m.grid_setup();
        let mut cpu = CpuBackend::new(&setup).expect("cpu backend");
        convolution(&mut c, &mut cpu, &m);
        match GpuContext::new(AdapterPreference::Best).and_then(|ctx| GpuBackend::new(ctx, &setup))
        {
            Ok(mut gpu) => convolution(&mut c, &mut gpu, &m),
            Err(e) => eprintln!("GPU convolution at {n}² skipped: {e}"),
        }
    }
    c.final_summary();
}
