//! CG solves that failed in the normal mode and were retried in the safer one, and the
//! warnings a run gives about them.

use super::cg::{CgEnd, CgReport, REPLACE_EVERY, TRUE_RESIDUAL_SLACK};
use crate::model::CgSettings;
use crate::params::{
    BACKEND, CG_ACCEPT, CG_MAX_ITERATIONS, CG_TOLERANCE, PRECISION, PRECONDITIONER, STEPS,
};

/// What became of a safer retry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RetryVerdict {
    /// It reached the tolerance: the state is as good as any.
    Converged,
    /// It stopped above the tolerance but within the acceptable residual: the run goes on
    /// and the state is marked by its `cg_residual`.
    Accepted,
    /// It stopped above the acceptable residual: the run ends with an error.
    Failed,
}

/// A CG solve that did not converge in the normal mode and was retried in the safer mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CgRetry {
    /// Approach of the solve (dimensionless d̄).
    pub d_bar: f64,
    /// How the normal mode ended.
    pub first: CgReport,
    /// How the safer retry ended (its residual is that of the p kept).
    pub retry: CgReport,
    /// What became of it.
    pub verdict: RetryVerdict,
}

impl CgRetry {
    /// Judge a retry against the settings' tolerance and acceptable residual.
    pub fn new(d_bar: f64, first: CgReport, retry: CgReport, settings: &CgSettings) -> Self {
        let verdict = if retry.converged() {
            RetryVerdict::Converged
        } else if retry.residual <= settings.acceptable() {
            RetryVerdict::Accepted
        } else {
            RetryVerdict::Failed
        };
        CgRetry {
            d_bar,
            first,
            retry,
            verdict,
        }
    }

    /// CG iterations of both attempts.
    pub fn iterations(&self) -> usize {
        self.first.iterations + self.retry.iterations
    }
}

/// The warning for a run whose backend stopped CG at its precision floor `floor` (relative
/// residual), far above the tolerance asked for (more than [`TRUE_RESIDUAL_SLACK`] times it,
/// what a solve would otherwise accept); `None` otherwise, `worst` being the worst residual
/// of its states.
pub fn floor_warning(
    floor: f64,
    settings: &CgSettings,
    precision: &str,
    worst: Option<f64>,
) -> Option<String> {
    (floor > TRUE_RESIDUAL_SLACK * settings.tolerance).then(|| {
        format!(
            "CG stopped at the {precision} precision floor of this backend, at relative \
             residual {floor:.1e}, above {CG_TOLERANCE} {:.1e}, which {precision} cannot \
             reach (the worst state's residual, in the cg_residual column of the states CSV: \
             {}); use {BACKEND} cpu with {PRECISION} f64 to reach it",
            settings.tolerance,
            worst.map_or("—".into(), |w| format!("{w:.2e}"))
        )
    })
}

/// What to try when CG ended as `end` above the tolerance.
pub fn advice(end: CgEnd) -> String {
    match end {
        CgEnd::Stagnated | CgEnd::ResidualGap | CgEnd::Converged => format!(
            "the tolerance is below what this arithmetic reaches: use a looser {CG_TOLERANCE} \
             (or, in f32, {BACKEND} cpu with {PRECISION} f64)"
        ),
        CgEnd::Diverged | CgEnd::NonFinite => format!(
            "try {PRECONDITIONER} stiffness, more {STEPS}, or (in f32) {BACKEND} cpu with \
             {PRECISION} f64"
        ),
        CgEnd::IterationLimit => format!(
            "raise {CG_MAX_ITERATIONS}, use {PRECONDITIONER} stiffness, or loosen {CG_TOLERANCE}"
        ),
    }
}

/// Warnings for the user about the retries of a run (none when there were none): how the
/// first one came about, how many reached the tolerance, and which were accepted above it.
pub fn warnings(retries: &[CgRetry], settings: &CgSettings) -> Vec<String> {
    let Some(first) = retries.first() else {
        return Vec::new();
    };
    let mut out = vec![format!(
        "CG was retried in a safer mode (every iteration checked, restarted from the true \
         residual at least every {REPLACE_EVERY} iterations) in {} solve(s); the first, at \
         d̄ = {:.5}, {} after {} iterations at relative residual {:.2e}",
        retries.len(),
        first.d_bar,
        first.first.end,
        first.first.iterations,
        first.first.residual
    )];
    let count = |v| retries.iter().filter(|r| r.verdict == v).count();
    let converged = count(RetryVerdict::Converged);
    if converged > 0 {
        out.push(format!(
            "{converged} retr{} reached {CG_TOLERANCE} {:.1e}",
            if converged == 1 { "y" } else { "ies" },
            settings.tolerance
        ));
    }
    let accepted = count(RetryVerdict::Accepted);
    let worst = retries
        .iter()
        .filter(|r| r.verdict == RetryVerdict::Accepted)
        .max_by(|a, b| a.retry.residual.total_cmp(&b.retry.residual));
    if let Some(w) = worst {
        let (ies, were) = if accepted == 1 {
            ("y", "was")
        } else {
            ("ies", "were")
        };
        out.push(format!(
            "{accepted} retr{ies} stopped above {CG_TOLERANCE} {:.1e} and {were} accepted \
             (relative residual ≤ {CG_ACCEPT} {:.1e}); the worst, at d̄ = {:.5}, {} at relative \
             residual {:.2e} after {} iterations in all. Those states carry their residual in \
             the cg_residual column of the states CSV; {}",
            settings.tolerance,
            settings.acceptable(),
            w.d_bar,
            w.retry.end,
            w.retry.residual,
            w.iterations(),
            advice(w.retry.end)
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings() -> CgSettings {
        CgSettings {
            tolerance: 1e-11,
            max_iterations: 5000,
            check_every: 2,
            accept: 1e-5,
        }
    }

    fn report(end: CgEnd, iterations: usize, residual: f64) -> CgReport {
        CgReport {
            iterations,
            residual,
            best: residual,
            end,
            convolutions: 0,
            error_estimate: None,
        }
    }

    #[test]
    fn no_retry_gives_no_warning() {
        assert!(warnings(&[], &settings()).is_empty());
    }

    #[test]
    fn a_retry_is_judged_against_the_tolerance_and_the_acceptable_residual() {
        let s = settings();
        let first = report(CgEnd::ResidualGap, 14, 8.6e-8);
        let judge = |end, r| CgRetry::new(2.25, first, report(end, 56, r), &s).verdict;
        assert_eq!(judge(CgEnd::Converged, 1e-12), RetryVerdict::Converged);
        assert_eq!(judge(CgEnd::Stagnated, 8.6e-8), RetryVerdict::Accepted);
        assert_eq!(judge(CgEnd::Stagnated, 2e-5), RetryVerdict::Failed);
    }

    #[test]
    fn accepted_retries_are_reported_with_the_worst_residual_and_what_to_change() {
        let s = settings();
        let first = report(CgEnd::ResidualGap, 14, 8.62e-8);
        let retries = [
            CgRetry::new(2.25, first, report(CgEnd::Stagnated, 56, 8.6e-8), &s),
            CgRetry::new(1.98, first, report(CgEnd::Stagnated, 54, 9.41e-8), &s),
            CgRetry::new(1.71, first, report(CgEnd::Converged, 3, 1e-12), &s),
        ];
        let w: Vec<String> = warnings(&retries, &s)
            .iter()
            .map(|w| crate::params::words::flags(w))
            .collect();
        assert_eq!(w.len(), 3, "{w:#?}");
        assert!(
            w[0].contains("in 3 solve(s)") && w[0].contains("8.62e-8"),
            "{}",
            w[0]
        );
        assert!(
            w[1].starts_with("1 retry reached --cg-tolerance 1.0e-11"),
            "{}",
            w[1]
        );
        for needle in [
            "2 retries",
            "9.41e-8",
            "d̄ = 1.98000",
            "68 iterations",
            "cg_residual",
        ] {
            assert!(w[2].contains(needle), "lacks {needle}: {}", w[2]);
        }
        assert!(w[2].contains("--cg-tolerance"), "{}", w[2]);
    }
}
