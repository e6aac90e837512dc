//! The convergence law of the mesh-dependent criterion (physics §7): the adhesive force is
//! over-predicted at first order in Δx, by about k/n_d with n_d the number of elements across
//! the contact's minor axis at the force minimum. Used to warn about coarse grids and to
//! choose a grid for a requested accuracy.

use super::line_fit::{fit_free_line, Point};
use crate::params::{ACCURACY, EXTRAPOLATE, GRID, REGRID};

/// The reference table (`jkrbem reference`), compiled in: the law is fitted to it.
const REFERENCE_TABLE: &str = include_str!("../../data/reference/adhesive-force.csv");

/// The spread of k (relative, one standard deviation) that remains where the limit is known
/// exactly: the sphere's seven runs with the apex on an element corner (64²–256², fixed and
/// re-gridded, n_d = 24–198) give k = 3.0–3.33 against JKR's exact 1/2.
pub const K_GRID_SPREAD: f64 = 0.05;

/// The relative spread of k where neither the table nor the sphere fixes it: the first
/// extrapolations (0.2–0.7 % of |min F̄|) left about 15 % of the correction at n_d ≈ 100.
pub const K_UNTABLED_SPREAD: f64 = 0.15;

/// k measured per ratio before the table (physics §7): 3.2 (sphere), 2.9 (2), 2.2 (5), 2.0
/// (10), 1.65 (25), 1.5 (50).
pub const K_MEASURED: [(f64, f64); 6] = [
    (1.0, 3.2),
    (2.0, 2.9),
    (5.0, 2.2),
    (10.0, 2.0),
    (25.0, 1.65),
    (50.0, 1.5),
];

/// The sphere's k, measured against JKR's exact 1/2 (seven runs, 64²–256², fixed and
/// re-gridded, apex on an element corner), with [`K_GRID_SPREAD`].
pub const SPHERE: LawPoint = LawPoint {
    ratio: 1.0,
    k: 3.2,
    k_sd: K_GRID_SPREAD,
};

/// One ratio of the law: R1/R2, k and k's relative standard deviation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawPoint {
    /// R1/R2.
    pub ratio: f64,
    /// k (dimensionless).
    pub k: f64,
    /// k's relative standard deviation.
    pub k_sd: f64,
}

/// The law's points: at each ratio of the reference table, k from the smooth law fitted to
/// the table ([`fit_table_law`]: the sphere's 3.2 and every row's fitted k, pooled), with its
/// relative spread: the law's own uncertainty there combined with [`K_GRID_SPREAD`] (how far
/// one grid's k moves, which a single run does not average away). Beyond the table's largest
/// ratio, [`K_MEASURED`] with [`K_UNTABLED_SPREAD`]. With fewer than two rows, the rows as they
/// are and [`K_MEASURED`] elsewhere (the sphere: [`SPHERE`]).
pub fn law_points() -> &'static [LawPoint] {
    static POINTS: std::sync::OnceLock<Vec<LawPoint>> = std::sync::OnceLock::new();
    POINTS.get_or_init(|| law_points_of(&table_points(REFERENCE_TABLE)))
}

/// [`law_points`] for the table points `rows` (see [`table_points`]).
pub fn law_points_of(rows: &[LawPoint]) -> Vec<LawPoint> {
    let mut points = Vec::new();
    let law = fit_table_law(rows);
    let largest = rows.iter().map(|p| p.ratio).fold(1.0, f64::max);
    // Where no law can be fitted, the rows themselves (and [`K_MEASURED`] elsewhere).
    if let Some(law) = &law {
        // The sphere's k is measured against its exact limit, better than the law pools it.
        points.push(SPHERE);
        for p in rows {
            points.push(law.at(p.ratio));
        }
    } else {
        points.extend_from_slice(rows);
    }
    for &(ratio, k) in &K_MEASURED {
        let covered = law.is_some() && ratio <= largest;
        if !covered && !points.iter().any(|p| p.ratio == ratio) {
            let k_sd = if ratio == 1.0 {
                K_GRID_SPREAD
            } else {
                K_UNTABLED_SPREAD
            };
            points.push(LawPoint { ratio, k, k_sd });
        }
    }
    points.sort_by(|a, b| a.ratio.total_cmp(&b.ratio));
    points.dedup_by(|a, b| a.ratio == b.ratio);
    points
}

/// The smooth law k = k_slender + k_round/(R1/R2), fitted by weighted least squares to the
/// sphere's k (3.2, one standard deviation [`K_GRID_SPREAD`]) and each table row's k (one
/// standard deviation: its `k_sd` without [`K_GRID_SPREAD`]), with its parameters'
/// covariance widened by the Birge ratio where the rows scatter more than that.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableLaw {
    /// k of an infinitely slender contact (the constant term).
    pub k_slender: f64,
    /// The term in 1/(R1/R2).
    pub k_round: f64,
    /// Covariance of (k_slender, k_round), Birge-widened.
    pub covariance: [[f64; 2]; 2],
}

impl TableLaw {
    /// k at R1/R2 = `ratio`.
    pub fn k(&self, ratio: f64) -> f64 {
        self.k_slender + self.k_round / ratio
    }

    /// The standard deviation of [`TableLaw::k`] at `ratio` (absolute).
    pub fn k_sd(&self, ratio: f64) -> f64 {
        let g = [1.0, 1.0 / ratio];
        let c = &self.covariance;
        (g[0] * g[0] * c[0][0] + 2.0 * g[0] * g[1] * c[0][1] + g[1] * g[1] * c[1][1])
            .max(0.0)
            .sqrt()
    }

    /// The standard deviations of (k_slender, k_round) (absolute).
    pub fn sd(&self) -> (f64, f64) {
        let c = &self.covariance;
        (c[0][0].max(0.0).sqrt(), c[1][1].max(0.0).sqrt())
    }

    /// The law point at `ratio`: k and its relative spread for one run (the law's own
    /// uncertainty combined with [`K_GRID_SPREAD`]).
    pub fn at(&self, ratio: f64) -> LawPoint {
        let k = self.k(ratio);
        LawPoint {
            ratio,
            k,
            k_sd: K_GRID_SPREAD.hypot(self.k_sd(ratio) / k),
        }
    }
}

/// Fit [`TableLaw`] to the table points `rows` and the sphere. `None` with fewer than two
/// rows (the law is then [`K_MEASURED`]).
pub fn fit_table_law(rows: &[LawPoint]) -> Option<TableLaw> {
    if rows.len() < 2 {
        return None;
    }
    // (1/ratio, k, absolute sd) of every observation.
    let obs: Vec<(f64, f64, f64)> = std::iter::once(SPHERE)
        .chain(rows.iter().copied())
        .map(|p| {
            let own = if p.ratio == 1.0 {
                p.k_sd
            } else {
                (p.k_sd * p.k_sd - K_GRID_SPREAD * K_GRID_SPREAD)
                    .max(0.0)
                    .sqrt()
            };
            (1.0 / p.ratio, p.k, (own * p.k).max(1e-6))
        })
        .collect();
    let points: Vec<Point> = obs.iter().map(|&(x, y, sd)| Point { x, y, sd }).collect();
    let fit = fit_free_line(&points)?;
    let birge2 = fit.birge().powi(2);
    Some(TableLaw {
        k_slender: fit.intercept,
        k_round: fit.slope,
        covariance: [
            [birge2 * fit.intercept_sd.powi(2), birge2 * fit.covariance],
            [birge2 * fit.covariance, birge2 * fit.slope_sd.powi(2)],
        ],
    })
}

/// A reference table's CSV text: a lookup of a column's index by name, and the records that
/// could be read. `None` without a header.
fn read_table(csv_text: &str) -> Option<(impl Fn(&str) -> Option<usize>, Vec<csv::StringRecord>)> {
    let mut r = csv::Reader::from_reader(csv_text.as_bytes());
    let h = r.headers().ok()?.clone();
    let records = r.records().filter_map(Result::ok).collect();
    Some((move |name: &str| h.iter().position(|x| x == name), records))
}

/// The law points of a reference table's CSV text (rows without a value are skipped, and so
/// is the sphere's).
pub fn table_points(csv_text: &str) -> Vec<LawPoint> {
    let Some((col, records)) = read_table(csv_text) else {
        return Vec::new();
    };
    let (Some(ci), Some(cf), Some(cu), Some(ck), Some(cn)) = (
        col("ratio"),
        col("f_ad_bar"),
        col("f_ad_bar_uncertainty"),
        col("k"),
        col("n_d"),
    ) else {
        return Vec::new();
    };
    let cku = col("k_uncertainty");
    records
        .into_iter()
        .filter_map(|rec| {
            let num = |i: usize| rec.get(i)?.parse::<f64>().ok().filter(|v| v.is_finite());
            let (ratio, f, u, k, n_d) = (num(ci)?, num(cf)?, num(cu)?, num(ck)?, num(cn)?);
            if ratio == 1.0 || !(k > 0.0 && f > 0.0 && n_d > 0.0) {
                return None;
            }
            // The fit's own uncertainty of k where the table has it; else what the limit's
            // uncertainty leaves of the finest grid's correction k/n_d.
            let fitted = match cku.and_then(num) {
                Some(ku) => 0.5 * ku / k,
                None => 0.5 * u / f * n_d / k,
            };
            Some(LawPoint {
                ratio,
                k,
                k_sd: K_GRID_SPREAD.hypot(fitted),
            })
        })
        .collect()
}

/// One reference row's resolution: R1/R2, the finest grid's Nx and its n_d (elements across
/// the minor axis at the force minimum).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableResolution {
    /// R1/R2.
    pub ratio: f64,
    /// Nx of the row's finest grid.
    pub nx: usize,
    /// n_d of that grid's run.
    pub n_d: f64,
}

/// One reference row's value: |min F̄| at Δx → 0 with its stated half-width, the grids of the
/// ladder it came from and the finest grid's n_d.
#[derive(Debug, Clone, PartialEq)]
pub struct TableValue {
    /// R1/R2.
    pub ratio: f64,
    /// |min F̄| at Δx → 0 (dimensionless).
    pub f_ad_bar: f64,
    /// Its stated half-width (absolute).
    pub uncertainty: f64,
    /// The ladder's grids Nx, coarse to fine.
    pub grids: Vec<usize>,
    /// n_d of the finest grid's run at the default margin, where the table has it.
    pub n_d: Option<f64>,
    /// c̄ at the force minimum at Δx → 0 and its half-width (dimensionless), where the table
    /// has them.
    pub c_bar_at_min: Option<(f64, f64)>,
    /// d̄ at the force minimum at Δx → 0 and its half-width (dimensionless), where the table
    /// has them.
    pub d_bar_at_min: Option<(f64, f64)>,
}

/// The value of every row of a reference table's CSV text (rows without a value, its
/// uncertainty or grids are skipped).
pub fn table_values(csv_text: &str) -> Vec<TableValue> {
    let Some((col, records)) = read_table(csv_text) else {
        return Vec::new();
    };
    let (Some(ci), Some(cf), Some(cu), Some(cg)) = (
        col("ratio"),
        col("f_ad_bar"),
        col("f_ad_bar_uncertainty"),
        col("grids"),
    ) else {
        return Vec::new();
    };
    let cn = col("n_d");
    let pair = |value: &str, half_width: &str| col(value).zip(col(half_width));
    let (cc, cd) = (
        pair("c_bar_at_min", "c_bar_at_min_uncertainty"),
        pair("d_bar_at_min", "d_bar_at_min_uncertainty"),
    );
    records
        .into_iter()
        .filter_map(|rec| {
            let num = |i: usize| rec.get(i)?.parse::<f64>().ok().filter(|v| v.is_finite());
            let grids: Option<Vec<usize>> = rec
                .get(cg)?
                .split(';')
                .map(|g| g.trim().parse::<usize>().ok())
                .collect();
            Some(TableValue {
                ratio: num(ci)?,
                f_ad_bar: num(cf)?,
                uncertainty: num(cu)?,
                grids: grids.filter(|g| !g.is_empty())?,
                n_d: cn.and_then(num),
                c_bar_at_min: cc.and_then(|(v, u)| num(v).zip(num(u))),
                d_bar_at_min: cd.and_then(|(v, u)| num(v).zip(num(u))),
            })
        })
        .collect()
}

/// The compiled-in reference table's CSV text (`data/reference/adhesive-force.csv`).
pub fn reference_table_csv() -> &'static str {
    REFERENCE_TABLE
}

/// [`table_values`] of the compiled-in reference table.
pub fn reference_values() -> Vec<TableValue> {
    table_values(REFERENCE_TABLE)
}

/// The resolution of every row of a reference table's CSV text (rows without n_d, grids or a
/// value are skipped).
pub fn table_resolution(csv_text: &str) -> Vec<TableResolution> {
    table_values(csv_text)
        .into_iter()
        .filter_map(|v| {
            Some(TableResolution {
                ratio: v.ratio,
                nx: *v.grids.last()?,
                n_d: v.n_d.filter(|n| *n > 0.0)?,
            })
        })
        .collect()
}

/// [`table_resolution`] of the compiled-in reference table.
pub fn reference_resolution() -> Vec<TableResolution> {
    table_resolution(REFERENCE_TABLE)
}

/// Where `x` falls among `len` increasing abscissae (`x_at(i)`, all > 0), linear in ln x:
/// the indices of the points on either side and the weight of the second; beyond the ends
/// (or on a point) the end's (the point's) index twice or the lower one with weight 0.
/// Panics if `len` is 0.
pub fn ln_bracket(len: usize, x_at: impl Fn(usize) -> f64, x: f64) -> (usize, usize, f64) {
    let last = len - 1;
    if x >= x_at(last) {
        return (last, last, 0.0);
    }
    if x <= x_at(0) {
        return (0, 0, 0.0);
    }
    let i = (0..last).rev().find(|&i| x_at(i) <= x).unwrap_or(0);
    let (a, b) = (x_at(i).ln(), x_at(i + 1).ln());
    (i, i + 1, (x.ln() - a) / (b - a))
}

/// The two law points around `ratio` and the weight of the upper one (linear in ln R1/R2;
/// constant beyond the ends).
fn bracket(ratio: f64) -> (LawPoint, LawPoint, f64) {
    let p = law_points();
    let (i, j, t) = ln_bracket(p.len(), |i| p[i].ratio, ratio.max(1.0));
    (p[i], p[j], t)
}

/// The first-order coefficient k of R1/R2 (dimensionless) in |min F̄| ≈ F0·(1 + k/n_d),
/// measured against the program's own Δx → 0 limits (not against Johnson–Greenwood, which is
/// itself off by tens of per cent for slender contacts): from the reference table where it
/// has the ratio, else from the first measurements ([`law_points`]), linear in ln(R1/R2)
/// between them and constant beyond.
pub fn coefficient_central(ratio: f64) -> f64 {
    let (a, b, t) = bracket(ratio);
    a.k + t * (b.k - a.k)
}

/// The relative standard deviation of the law's k for R1/R2 (dimensionless), as the
/// estimators use it: the law point's (the larger of the two around a ratio between them).
pub fn k_relative_sd(ratio: f64) -> f64 {
    let (a, b, t) = bracket(ratio);
    if t == 0.0 {
        a.k_sd
    } else {
        a.k_sd.max(b.k_sd)
    }
}

/// The grid-phase scatter of one run's |min F̄| about the law (one standard deviation,
/// relative) is this over n_d for runs with the apex on an element corner (the default): the
/// sphere's seven such runs scatter by 0.12/n_d about k = 3.2.
pub const CORNER_SCATTER: f64 = 0.15;

/// The grid-phase scatter of one run's |min F̄| (one standard deviation, relative) is at most
/// about this over n_d for runs at other apex offsets: where the contact's edge falls between
/// element centres moves it by 0.22/n_d at n_d ≈ 34, 0.34/n_d at 62 and 0.22/n_d at 124
/// (the sphere, eight random apex offsets per grid; re-gridded 64²: 0.25/n_d). Their mean
/// over-prediction is lower than the corner's (k ≈ 2.2–2.5 for the sphere), which the
/// estimators cover by doubling k's spread.
pub const OFFSET_SCATTER: f64 = 0.35;

/// The grid-phase scatter of one run's c̄ and d̄ at the force minimum (one standard deviation,
/// absolute) is this times √(1/n_d) for runs with the apex on an element corner: the force is
/// flat at its minimum, so a scatter of the force ∝ 1/n_d moves where the lowest state lies by
/// ∝ √(1/n_d). Measured over 36 groups of five runs at domain margins 0.08…0.28 (R1/R2 1…50,
/// fixed and re-gridded, n_d 11…94): RMS of sd·√n_d 0.14 for c̄ and 0.15 for d̄. A force-like
/// 0.15·|c̄|/n_d is ten times too small at n_d ≈ 30, which made the Birge ratio of two runs'
/// c̄ fit state c̄ ± 0.9.
pub const POSITION_SCATTER: f64 = 0.15;

/// The slope of c̄ and d̄ at the force minimum against 1/n_d has no law; the estimators take it
/// as 0 ± k·this (absolute, k the force's convergence coefficient). Measured as the mean of a
/// grid's five margins against the reference row, |slope|/k is 0.2…0.5 (the sphere at n_d
/// 16…60 the largest, 10:1 at 15, 25:1 at 17, 50:1 at 11), c̄ too high and d̄ too low or
/// unbiased; c̄ and d̄ move by about the same absolute amount, so one scale serves both. With
/// 0.4 the coverage study's 180 single-run cases hold c̄ 177 times and d̄ 180 times (the
/// sphere's c̄ 28 of 30; with 0.3 only 24 of 30).
pub const POSITION_SLOPE: f64 = 0.4;

/// The range of k for R1/R2 (dimensionless): the central value ± 30 %, which holds every
/// ratio's measurements and random apex offsets too (physics §7).
pub fn coefficient(ratio: f64) -> (f64, f64) {
    let k = coefficient_central(ratio);
    (0.7 * k, 1.3 * k)
}

/// Expected relative error range of |min F̄| (dimensionless, positive: too large) with
/// `n_d` elements across the minor axis at the minimum, for R1/R2 = `ratio`.
pub fn expected_error(ratio: f64, n_d: f64) -> (f64, f64) {
    let (lo, hi) = coefficient(ratio);
    (lo / n_d, hi / n_d)
}

/// Elements across the minor axis at the minimum below which a run is called too coarse: below
/// it the grid is not yet in the first-order regime that the convergence law, the estimate's
/// correction and its stated uncertainty rest on (R1/R2 = 5 from 32×16, n_d = 12: observed
/// order −0.8; the coverage study's cases from n_d ≈ 20 hold their stated uncertainties). The
/// planner takes no grid below it, and one rule follows from it ([`answer_too_coarse`]): an
/// answer whose finest run is below it carries the warning and never meets a target.
pub const COARSE_N_D: f64 = 20.0;

/// How every too-coarse warning begins ([`coarse_grid_warning`]).
pub const COARSE_WARNING: &str = "too coarse a grid";

/// Whether an answer resting on runs whose finest has `finest_n_d` elements across the minor
/// axis at the minimum is too coarse: then it says so and states no target as met.
pub fn answer_too_coarse(finest_n_d: Option<f64>) -> bool {
    finest_n_d.is_none_or(|n| n < COARSE_N_D)
}

/// The elements n_d across the minor axis at the minimum that keep the expected error of
/// R1/R2 = `ratio` (its upper bound) within `target` (relative, e.g. 0.05).
pub fn n_d_for(ratio: f64, target: f64) -> f64 {
    coefficient(ratio).1 / target
}

/// A warning for a run with `n_d` elements across the minor axis at the minimum, if that is
/// below [`COARSE_N_D`].
pub fn coarse_grid_warning(ratio: f64, n_d: f64) -> Option<String> {
    if n_d >= COARSE_N_D {
        return None;
    }
    let (lo, hi) = expected_error(ratio, n_d);
    Some(format!(
        "{COARSE_WARNING}: only {n_d:.0} elements across the contact's minor axis at the force \
         minimum (at least {COARSE_N_D:.0} are needed for the first-order convergence the \
         estimate's correction and uncertainty rest on); the grid's own |min F̄| over-predicts \
         by about +{:.0}…{:.0} % here (docs/physics.md §7){} (n_d ≥ {:.0} for 10 % raw), \
         {ACCURACY}, {EXTRAPOLATE}, or {REGRID}",
        100.0 * lo,
        100.0 * hi,
        coarse_grid_advice(),
        n_d_for(ratio, 0.10).ceil()
    ))
}

/// Where the advice of a too-coarse warning ([`coarse_grid_warning`]) begins: what a
/// simulation can change. A command whose grids are fixed (the study) gives its own advice in
/// place of what follows.
pub fn coarse_grid_advice() -> String {
    format!("; use a finer {GRID}")
}

#[cfg(test)]
mod tests {

    #[test]
    fn ln_bracket_interpolates_in_ln_x_and_holds_the_ends() {
        let xs = [1.0, 4.0];
        let at = |x: f64| {
            let (i, j, t) = ln_bracket(2, |i| xs[i], x);
            let ys = [2.0, 4.0];
            ys[i] + t * (ys[j] - ys[i])
        };
        assert_eq!(at(2.0), 3.0);
        assert_eq!(at(9.0), 4.0);
        assert_eq!(at(0.5), 2.0);
        assert_eq!(ln_bracket(2, |i| xs[i], 1.0), (0, 0, 0.0));
    }

    use super::*;

    #[test]
    fn sphere_law_brackets_spec_measurements() {
        // physics §7: n_d = 23 → +13 %, 41 → +6.4 %, 86 → +3.4 %, 170 → +1.4 %.
        for (n_d, err) in [(23.0, 0.13), (41.0, 0.064), (86.0, 0.034), (170.0, 0.014)] {
            let (lo, hi) = expected_error(1.0, n_d);
            assert!(
                lo <= err * 1.1 && err <= hi,
                "n_d {n_d}: {lo}…{hi} vs {err}"
            );
        }
    }

    #[test]
    fn the_law_takes_k_and_its_spread_from_the_reference_table() {
        let csv = "ratio,f_ad_bar,f_ad_bar_uncertainty,c_bar_at_min,k,k_uncertainty,n_d,command\n\
                   1.0,0.4992,0.0012,0.78,3.31,0.2,198.0,x\n\
                   5.0,0.4899,0.0010,0.77,2.05,0.3,150.0,x\n\
                   7.0,,,,,,,x\n";
        let p = table_points(csv);
        assert_eq!(
            p.len(),
            1,
            "the sphere's limit is exact; an empty row is skipped: {p:?}"
        );
        assert_eq!((p[0].ratio, p[0].k), (5.0, 2.05));
        // ± 0.3 on k is two sd.
        let fitted: f64 = 0.5 * 0.3 / 2.05;
        assert!((p[0].k_sd - fitted.hypot(K_GRID_SPREAD)).abs() < 1e-12);
        // Without k's own uncertainty: what ± 0.0010 of 0.4899 leaves of k/n_d at n_d = 150.
        let old = "ratio,f_ad_bar,f_ad_bar_uncertainty,k,n_d\n5.0,0.4899,0.0010,2.05,150.0\n";
        let from_limit: f64 = 0.5 * 0.0010 / 0.4899 * 150.0 / 2.05;
        assert!((table_points(old)[0].k_sd - from_limit.hypot(K_GRID_SPREAD)).abs() < 1e-12);
        // The compiled-in law covers every ratio, with the sphere exact-based.
        assert_eq!(coefficient_central(1.0), 3.2);
        assert_eq!(k_relative_sd(1.0), K_GRID_SPREAD);
        for r in [1.0, 1.5, 3.0, 7.0, 50.0, 1000.0] {
            let (k, sd) = (coefficient_central(r), k_relative_sd(r));
            assert!(
                (1.0..4.0).contains(&k) && (0.0..=0.5).contains(&sd),
                "{r}: {k} {sd}"
            );
        }
    }

    #[test]
    fn the_smooth_law_pools_the_rows_and_is_tighter_than_any_one() {
        // Rows on k = 1.6 + 1.6/r exactly, each ± 10 % (one sd, with the grid spread).
        let rows: Vec<LawPoint> = [1.5, 2.0, 3.0, 5.0, 7.0, 10.0]
            .iter()
            .map(|&ratio| LawPoint {
                ratio,
                k: 1.6 + 1.6 / ratio,
                k_sd: 0.1,
            })
            .collect();
        let law = fit_table_law(&rows).unwrap();
        // The sphere's 3.2 lies on that law, so the fit is exact.
        assert!((law.k_slender - 1.6).abs() < 1e-9 && (law.k_round - 1.6).abs() < 1e-9);
        let points = law_points_of(&rows);
        assert_eq!(points[0], SPHERE);
        for p in &points[1..points.len() - 2] {
            assert!(p.k_sd < 0.1 && p.k_sd > K_GRID_SPREAD, "{p:?}");
        }
        // Beyond the table: the first measurements, with their spread.
        let last = points[points.len() - 1];
        assert_eq!((last.ratio, last.k_sd), (50.0, K_UNTABLED_SPREAD));
        // One row alone is no law: it is used as it is, the first measurements elsewhere.
        assert!(fit_table_law(&rows[..1]).is_none());
        let alone = law_points_of(&rows[..1]);
        assert_eq!(alone.len(), K_MEASURED.len() + 1);
        assert!(alone.contains(&rows[0]));
    }

    #[test]
    fn warning_only_below_threshold() {
        assert!(coarse_grid_warning(1.0, 50.0).is_none());
        let w = coarse_grid_warning(1.0, 12.0).unwrap();
        assert!(w.contains("12 elements") && w.contains("+19…35 %"), "{w}");
    }

    #[test]
    fn n_d_for_inverts_the_law() {
        let n = n_d_for(1.0, 0.05);
        assert!((expected_error(1.0, n).1 - 0.05).abs() < 1e-12);
    }
}
