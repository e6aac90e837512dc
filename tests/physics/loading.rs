//! The loading phase: a surface pressed on from its first touch, elements attaching where
//! their gap closes, then pulled off.

use crate::common;

use jkrbem::model::{ModelOptions, Preload};
use jkrbem::solver::{self, Phase, State};

/// The states after the first contact: the pull-off, from the state at d0 on.
fn from_d0(states: &[State]) -> Vec<&State> {
    let k = states
        .iter()
        .position(|s| !s.phase.is_loading())
        .expect("a pull-off");
    // The press's own state (the one-piece approach, or the last loading step) is where the
    // pull-off starts; compare from the first pull-off state on.
    states[k..]
        .iter()
        .filter(|s| s.phase != Phase::Approach)
        .collect()
}

#[test]
fn a_sphere_pressed_on_to_d0_pulls_off_as_the_one_piece_press_does() {
    for (ratio, nx) in [(1.0, 64), (3.0, 64)] {
        let options = ModelOptions {
            nx,
            ..Default::default()
        };
        let today = common::model_for(ratio, options.clone());
        let pressed = common::model_for(
            ratio,
            ModelOptions {
                preload: Some(Preload::StartRadius),
                ..options
            },
        );
        let loading = pressed.loading.expect("a loading phase");
        assert!(loading.d_touch >= 0.0 && loading.d_touch < 1e-2 * today.load.d0);
        let run = |m: &jkrbem::model::Model| {
            let out = solver::run(&mut common::cpu_backend(m), m, &mut |_| {});
            assert!(out.complete(), "{:?}", out.error);
            out
        };
        let (a, b) = (run(&today), run(&pressed));
        let loading_states: Vec<&State> =
            b.states.iter().filter(|s| s.phase.is_loading()).collect();
        assert!(loading_states.len() >= 2);
        // The press rises monotonically to d0, in contact from the first step.
        assert!(loading_states.windows(2).all(|w| w[1].d > w[0].d));
        let last = loading_states.last().unwrap();
        assert_eq!(last.d, today.load.d0);
        let press = &a.states[0];
        assert_eq!(press.phase, Phase::Approach);
        println!(
            "{ratio}:1 at {nx}²: pressed on in {} steps to d̄ = {:.4}: {} elements, F̄ = {:.6} \
             (one-piece press {} elements, F̄ = {:.6})",
            loading_states.len(),
            last.d_bar,
            last.n_contact,
            last.f_bar,
            press.n_contact,
            press.f_bar
        );
        assert_eq!(last.n_contact, press.n_contact, "the same contact at d0");
        assert!((last.force / press.force - 1.0).abs() < 1e-6);
        let (pa, pb) = (from_d0(&a.states), from_d0(&b.states));
        assert_eq!(pa.len(), pb.len());
        for (x, y) in pa.iter().zip(&pb) {
            assert_eq!((x.phase, x.n_contact), (y.phase, y.n_contact));
            assert!(
                (x.d - y.d).abs() <= 1e-6 * x.d.abs().max(1.0),
                "{x:?} {y:?}"
            );
            assert!(
                (x.force - y.force).abs() <= 1e-6 * x.force.abs().max(press.force.abs() * 1e-3),
                "{x:?}\n{y:?}"
            );
        }
        let (fa, fb) = (a.force_minimum().unwrap(), b.force_minimum().unwrap());
        assert!(
            (fa.f_bar / fb.f_bar - 1.0).abs() < 1e-6,
            "{} vs {}",
            fa.f_bar,
            fb.f_bar
        );
    }
}

#[test]
fn a_rough_sphere_is_pressed_on_then_pulled_off() {
    let run = |scene: &jkrbem::scene::Scene| {
        let model = jkrbem::model::Model::build(
            scene,
            &ModelOptions {
                nx: 64,
                ..Default::default()
            },
        )
        .unwrap();
        assert!(model.loading.is_some(), "a rough shape is pressed on");
        let out = solver::run(&mut common::cpu_backend(&model), &model, &mut |_| {});
        assert!(out.complete() && out.min_reached(), "{:?}", out.error);
        out
    };
    let smooth = common::run_ratio(
        1.0,
        ModelOptions {
            nx: 64,
            ..Default::default()
        },
    );
    let f_smooth = -smooth.outcome.force_minimum().unwrap().f_bar;
    // The zero roughness of a zero slope is the smooth sphere.
    let flat = run(&common::rough_sphere(1e-9, 1));
    let f_flat = -flat.force_minimum().unwrap().f_bar;
    assert!(
        (f_flat / f_smooth - 1.0).abs() < 1e-4,
        "{f_flat} vs {f_smooth}"
    );
    for seed in [1, 2] {
        let out = run(&common::rough_sphere(0.05, seed));
        let phases: Vec<Phase> = out.states.iter().map(|s| s.phase).collect();
        let first_pull = phases.iter().position(|&p| !p.is_loading()).unwrap();
        assert!(first_pull > 2, "loading first");
        assert!(phases[first_pull..].iter().all(|&p| !p.is_loading()));
        let min = out.force_minimum().unwrap();
        assert!(!min.phase.is_loading());
        println!(
            "rough sphere 64², rms slope 0.05, seed {seed}: |min F̄| = {:.4} (smooth {f_smooth:.4}), \
             {} loading states",
            -min.f_bar, first_pull
        );
        // Roughness of slope 0.05 lowers the sphere's pull-off a little, never to nothing.
        assert!(-min.f_bar > 0.3 * f_smooth && -min.f_bar < 1.2 * f_smooth);
    }
}

/// A wavy map h = 0.02 (1 − cos 2πx)(1 + 0.3 cos πy) (lengths in the map's unit), 4 × 4 at
/// node spacing 1/32: its crests' minima lie along lines, so it has no apex and is placed on
/// its whole extent.
fn wavy_map() -> jkrbem::scene::Indenter {
    let (n, s) = (129, 1.0 / 32.0);
    let mut heights = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f64 * s - 2.0, j as f64 * s - 2.0);
            let wave = 1.0 - (2.0 * std::f64::consts::PI * x).cos();
            heights.push(0.02 * wave * (1.0 + 0.3 * (std::f64::consts::PI * y).cos()));
        }
    }
    let map = jkrbem::scene::height_map::HeightMap::new(n, n, s, heights).unwrap();
    let surface = jkrbem::scene::MeasuredSurface::new(map, "wavy map").unwrap();
    jkrbem::scene::Indenter::HeightMap(std::sync::Arc::new(surface))
}

#[test]
fn a_strongly_adhesive_map_on_a_window_pulls_off_in_its_planned_steps() {
    // E* = Δγ = 1 in the map's units: the press is some 1e-3 deep, the pull-off runs to
    // approaches of order Kendall's √(2π Δγ a / E*) ≈ 2 for the pressed contact's radius a.
    // Steps sized from the press alone would take ~1e5 of them.
    let scene = jkrbem::scene::Scene::with_indenter(wavy_map(), 1.0, 1.0).unwrap();
    let options = ModelOptions {
        nx: 32,
        ..Default::default()
    };
    let model = jkrbem::model::Model::build(&scene, &options).unwrap();
    let loading = model.loading.expect("a map on a window is pressed on");
    let depth = model.load.d0 - loading.d_touch;
    let out = solver::run(&mut common::cpu_backend(&model), &model, &mut |_| {});
    assert!(out.complete(), "{:?}", out.error);
    let min = out.force_minimum().expect("a force minimum");
    let last = out.states.last().unwrap();
    println!(
        "wavy map 32²: depth {depth:.3e}, load step {:.3e}, {} states; min F = {:.4} at d = {:.4}; \
         last state d = {:.4} with {} elements",
        model.load.d_step,
        out.states.len(),
        min.force,
        min.d,
        last.d,
        last.n_contact
    );
    assert!(out.min_reached());
    // The pull-off is adhesive: it ends far below the first touch, within the planned path.
    assert!(loading.d_touch - min.d > 100.0 * depth);
    assert!(min.d > model.load.d_end && min.force < 0.0);
    assert!(out.states.len() < 2 * options.steps + 100);
}
