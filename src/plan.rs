//! Modelling no more than a scene needs: from a requested accuracy of the adhesive force,
//! choose the grid, the domain, the load steps and what to compute, by the convergence law
//! (SPEC §7, [`crate::analysis::convergence`]).

use crate::analysis::convergence;
use crate::model::{self, Measure, Model, ModelError, ModelOptions, Stepping, MAX_GRID};
use crate::scene::Scene;
use crate::text::compact;
use crate::theory::{self, TheoryModel};

/// Smallest grid side a plan uses (elements): coarser grids are not yet in the first-order
/// regime (the observed order from 32/64/128 was 1.1, from 64/128/256 without re-gridding 0.6).
pub const MIN_PLAN_GRID: usize = 32;

/// Predicted elements across the minor axis at the minimum on the coarsest grid of an
/// extrapolation: coarser grids are not yet first order (R1/R2 = 5 from 32×16, n_d = 12:
/// observed order −0.8).
pub const MIN_EXTRAPOLATION_N_D: f64 = 20.0;

/// Largest grid side a plan runs directly; finer answers come from extrapolation.
pub const MAX_DIRECT_GRID: usize = 256;

/// Targets below this (relative) are met by extrapolating three grids to Δx → 0, whose
/// finest grid alone is expected within 4× the target; so are larger ones when that finest
/// grid is smaller than the single grid that would meet the target.
pub const EXTRAPOLATE_BELOW: f64 = 0.03;

/// Δx at the force minimum over the initial Δx with re-gridding, from c̄0 = 1.5: measured
/// 0.60–0.63 (R1/R2 = 1 and 5, 64²–256²) and 0.50 (R1/R2 = 25, 128×32); the last re-grid
/// falls at c̄ ≤ 1.125, so 0.75 would be the bound.
pub const REGRID_DX_GAIN: f64 = 0.65;

/// Load steps of a plan: with adaptive stepping the force minimum does not depend on them
/// (measured: 0.5155 with 100 and 200 steps, 128², re-gridded).
pub const PLAN_STEPS: usize = 100;

/// What a requested accuracy led to.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Grids Nx to run, coarse to fine (one: a direct answer; three: extrapolated).
    pub grids: Vec<usize>,
    /// The options each grid is run with (nx set per grid).
    pub options: ModelOptions,
    /// Predicted elements across the minor axis at the minimum on the finest grid.
    pub n_d: f64,
    /// Predicted relative error range of the finest grid alone (first order).
    pub finest_error: (f64, f64),
    /// The target (relative).
    pub target: f64,
}

impl Plan {
    /// Whether the answer is extrapolated from several grids.
    pub fn extrapolates(&self) -> bool {
        self.grids.len() > 1
    }

    /// What was chosen and why, for the user.
    pub fn describe(&self, ratio: f64) -> String {
        let (lo, hi) = self.finest_error;
        let how = if self.extrapolates() {
            format!(
                "extrapolate |min F̄| to Δx → 0 from grids {:?} (the finest alone: +{:.1}…{:.1} %)",
                self.grids,
                100.0 * lo,
                100.0 * hi
            )
        } else {
            format!(
                "grid {} directly (expected error +{:.1}…{:.1} %)",
                self.grids[0],
                100.0 * lo,
                100.0 * hi
            )
        };
        format!(
            "--accuracy {:.3} %: R1/R2 = {ratio}: {how}; about {:.0} elements across the minor \
             axis at the minimum; domain: the initial contact c̄0 = {} plus {} % margin, re-gridded \
             to the shrinking contact (finer Δx, same grid); load steps: {} adaptive, stopped once \
             the force minimum is confirmed (--measure adhesive-force); precision: the backend's \
             (f32 on a GPU is 1e-6 relative, far below the target)",
            100.0 * self.target,
            self.n_d,
            self.options.start_radius_bar,
            100.0 * self.options.margin,
            self.options.steps,
        )
    }
}

/// Predicted elements across the minor axis at the force minimum for a model, re-gridded:
/// the closed form's b̄ at the minimum over the Δx expected there.
fn predicted_n_d(model: &Model) -> f64 {
    let ratio = model.scene.ratio();
    let b_bar = theory::pull_off(TheoryModel::adhesive_reference(ratio), ratio)
        .map(|p| p.force_min.b_bar)
        .unwrap_or(0.5);
    2.0 * b_bar * model.scene.scales().length / (model.dx * REGRID_DX_GAIN)
}

/// The cheapest plan expected to reach relative accuracy `target` (e.g. 0.01) on `scene`,
/// starting from the user's `base` options (CG settings, start radius, margin are kept).
pub fn for_accuracy(scene: &Scene, target: f64, base: &ModelOptions) -> Result<Plan, ModelError> {
    if !(target.is_finite() && target > 0.0 && target < 1.0) {
        return Err(ModelError::Invalid {
            flag: "--accuracy",
            value: format!("{}", 100.0 * target),
            expected: "a percentage in (0, 100), e.g. 5% or 1%".into(),
        });
    }
    let ratio = scene.ratio();
    let options = ModelOptions {
        ny: None,
        steps: PLAN_STEPS,
        stepping: Stepping::Adaptive,
        measure: Measure::AdhesiveForce,
        regrid: true,
        ..base.clone()
    };
    // The smallest grid whose predicted n_d meets a relative target, and that n_d. Grids too
    // coarse to resolve the contact at all are skipped.
    let grid_for = |t: f64| -> Result<(usize, f64), ModelError> {
        let needed = convergence::n_d_for(ratio, t);
        let mut nx = MIN_PLAN_GRID;
        loop {
            let built = Model::build(
                scene,
                &ModelOptions {
                    nx,
                    ..options.clone()
                },
            );
            let model = match built {
                Err(ModelError::TooCoarse { .. }) if nx < MAX_GRID => {
                    nx *= 2;
                    continue;
                }
                other => other?,
            };
            let n_d = predicted_n_d(&model);
            if n_d >= needed || nx >= 8 * MAX_DIRECT_GRID {
                return Ok((nx, n_d));
            }
            nx *= 2;
        }
    };
    let (direct, direct_n_d) = grid_for(target)?;
    // Or three grids whose finest alone is expected within 4× the target, extrapolated.
    let (nx, n_d) = grid_for(4.0 * target)?;
    let (coarsest, _) = grid_for(convergence::coefficient(ratio).1 / MIN_EXTRAPOLATION_N_D)?;
    let finest = nx.max(4 * coarsest);
    let extrapolate = target < EXTRAPOLATE_BELOW || direct > MAX_DIRECT_GRID || finest < direct;
    let (grids, n_d) = if extrapolate {
        (
            vec![finest / 4, finest / 2, finest],
            n_d * finest as f64 / nx as f64,
        )
    } else {
        (vec![direct], direct_n_d)
    };
    Ok(Plan {
        grids,
        options,
        n_d,
        finest_error: convergence::expected_error(ratio, n_d),
        target,
    })
}

/// The memory this machine can give a run (bytes): the smaller of the memory available now
/// (`MemAvailable` in /proc/meminfo) and what the process's control group may still use; or
/// the value of the environment variable `JKRBEM_MEMORY_LIMIT` (bytes) if set, to plan for
/// less. `None` where neither can be read (the check is then skipped).
pub fn available_memory() -> Option<u64> {
    if let Some(v) = std::env::var("JKRBEM_MEMORY_LIMIT")
        .ok()
        .and_then(|v| v.trim().parse::<f64>().ok())
    {
        return Some(v.max(0.0) as u64);
    }
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok();
    let available = meminfo.as_deref().and_then(|m| {
        m.lines()
            .find(|l| l.starts_with("MemAvailable:"))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|kb| kb.parse::<u64>().ok())
            .map(|kb| kb * 1024)
    });
    let read = |p: &str| {
        std::fs::read_to_string(p)
            .ok()
            .and_then(|t| t.trim().parse::<u64>().ok())
    };
    let cgroup = read("/sys/fs/cgroup/memory.max")
        .map(|max| max.saturating_sub(read("/sys/fs/cgroup/memory.current").unwrap_or(0)));
    match (available, cgroup) {
        (Some(a), Some(c)) => Some(a.min(c)),
        (a, c) => a.or(c),
    }
}

/// Bytes in words: "8.8 TB", "420 MB".
pub fn bytes_text(b: u64) -> String {
    let b = b as f64;
    let (v, unit) = if b >= 1e12 {
        (b / 1e12, "TB")
    } else if b >= 1e9 {
        (b / 1e9, "GB")
    } else {
        (b / 1e6, "MB")
    };
    format!("{} {unit}", compact(((v * 10.0).round() / 10.0).max(0.1)))
}

/// Refuse runs whose memory estimate exceeds what the machine has ([`available_memory`]):
/// `models` run `jobs` at a time, so the `jobs` largest must fit together. `flag` names the
/// grid flag in the message, which gives the estimate and the largest grid that fits.
pub fn check_memory(models: &[&Model], jobs: usize, flag: &'static str) -> Result<(), ModelError> {
    check_memory_within(models, jobs, flag, available_memory())
}

/// [`check_memory`] against `available` bytes (no check if `None`).
pub fn check_memory_within(
    models: &[&Model],
    jobs: usize,
    flag: &'static str,
    available: Option<u64>,
) -> Result<(), ModelError> {
    let Some(available) = available else {
        return Ok(());
    };
    let mut needs: Vec<(u64, &Model)> = models.iter().map(|m| (m.memory_estimate(), *m)).collect();
    needs.sort_by_key(|n| std::cmp::Reverse(n.0));
    let jobs = jobs.max(1).min(needs.len().max(1));
    let total: u64 = needs.iter().take(jobs).map(|n| n.0).sum();
    if total <= available {
        return Ok(());
    }
    let (_, big) = needs[0];
    // The largest power-of-two Nx (same aspect) whose `jobs` runs fit.
    let aspect = big.ny as f64 / big.nx as f64;
    let mut fits = None;
    let mut nx = model::MIN_GRID;
    while nx <= MAX_GRID {
        let ny = ((nx as f64 * aspect).round() as usize).max(model::MIN_GRID);
        if model::memory_estimate(nx, ny).saturating_mul(jobs as u64) <= available {
            fits = Some((nx, ny));
        }
        nx *= 2;
    }
    let at_a_time = if jobs > 1 {
        format!(" ({jobs} runs at a time with --jobs {jobs})")
    } else {
        String::new()
    };
    Err(ModelError::Invalid {
        flag,
        value: format!("{}", big.nx),
        expected: format!(
            "a {}×{} grid needs about {}{at_a_time}, more than the {} this machine has \
             available; {}",
            big.nx,
            big.ny,
            bytes_text(total),
            bytes_text(available),
            match fits {
                Some((n, _)) if flag.starts_with("--grid") => {
                    format!("the largest grid that fits is {flag} {n}")
                }
                Some((n, ny)) => format!("the largest grid that fits is {n}×{ny}"),
                None => "no grid fits".to_string(),
            }
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere() -> Scene {
        Scene::from_ratio(1.0, 1.0, 1.0, 1.0).unwrap()
    }

    #[test]
    fn looser_targets_take_coarser_grids() {
        let base = ModelOptions::default();
        let p10 = for_accuracy(&sphere(), 0.10, &base).unwrap();
        let p5 = for_accuracy(&sphere(), 0.05, &base).unwrap();
        assert_eq!(p10.grids.len(), 1);
        assert_eq!(p5.grids.len(), 1);
        assert!(p10.grids[0] < p5.grids[0], "{p10:?} {p5:?}");
        assert!(p5.finest_error.1 <= 0.05);
    }

    #[test]
    fn one_percent_extrapolates_three_grids() {
        let p = for_accuracy(&sphere(), 0.01, &ModelOptions::default()).unwrap();
        assert!(p.extrapolates());
        assert_eq!(p.grids.len(), 3);
        assert!(p.finest_error.1 <= 0.04, "{p:?}");
        assert!(p.options.regrid && p.options.measure == Measure::AdhesiveForce);
    }

    #[test]
    fn a_grid_larger_than_memory_is_refused_with_the_largest_that_fits() {
        let m = Model::build(
            &sphere(),
            &ModelOptions {
                nx: 4096,
                ..ModelOptions::default()
            },
        )
        .unwrap();
        let available = 1_000_000_000;
        let e = check_memory_within(&[&m], 1, "--grid", Some(available))
            .unwrap_err()
            .to_string();
        assert!(e.contains("--grid") && e.contains("4096×4096"), "{e}");
        // 1024² needs 64 MiB + 320 B × 1024² = 403 MB; 2048² 1.4 GB.
        assert!(
            e.contains("the largest grid that fits is --grid 1024"),
            "{e}"
        );
        assert!(e.contains("5.4 GB") && e.contains("1 GB"), "{e}");
        assert!(check_memory_within(&[&m], 1, "--grid", Some(u64::MAX)).is_ok());
        // Two at a time need twice as much.
        let small = Model::build(
            &sphere(),
            &ModelOptions {
                nx: 1024,
                ..ModelOptions::default()
            },
        )
        .unwrap();
        let room = 700_000_000;
        assert!(check_memory_within(&[&small, &small], 1, "--grid", Some(room)).is_ok());
        let e = check_memory_within(&[&small, &small], 2, "--grid", Some(room)).unwrap_err();
        assert!(e.to_string().contains("--jobs 2"), "{e}");
    }

    #[test]
    fn slender_scenes_skip_grids_too_coarse_to_resolve_them() {
        let s = Scene::from_ratio(50.0, 1.0, 1.0, 1.0).unwrap();
        let p = for_accuracy(&s, 0.05, &ModelOptions::default()).unwrap();
        assert!(p.grids[0] >= 64, "{p:?}");
    }

    #[test]
    fn bad_targets_are_refused() {
        for t in [0.0, -0.1, 1.5, f64::NAN] {
            let e = for_accuracy(&sphere(), t, &ModelOptions::default()).unwrap_err();
            assert!(e.to_string().contains("--accuracy"), "{e}");
        }
    }
}
