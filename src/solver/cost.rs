//! The cost account of a pull-off: what it did (load steps, detachment onsets, cascade
//! rounds, CG solves and iterations, convolutions outside CG) in all and per band of the mean
//! contact radius c̄, so that anyone can see where a run spends its time.
//!
//! A pull-off costs (solves) × (CG iterations per solve) × (time per iteration), plus the
//! convolutions a solve makes outside its iterations (its start residual and the check of
//! its true residual). CG iterations are device-independent: the GPU and the CPU make the
//! same ones for the same states (within f32's round-off).

use serde::{Deserialize, Serialize};

/// Work of the linear solver behind one or more states.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Work {
    /// CG solves on a fixed contact set (a safer retry counts as part of its solve).
    pub solves: usize,
    /// Of those, the solves made to CG's tolerance: the probes, the first press and a
    /// cascade's exact rounds (the others are its loose rounds,
    /// [`crate::solver::equilibrium`]).
    #[serde(default)]
    pub exact_solves: usize,
    /// CG iterations (one convolution of a search direction each).
    pub cg_iterations: usize,
    /// Convolutions u = K p made outside CG's iterations: a solve's start residual, the
    /// check of its true residual, the displacement of a pressure known without a solve.
    pub convolutions: usize,
    /// Detachment/attachment sweeps that changed the contact set (cascade rounds).
    pub rounds: usize,
    /// Elements detached without a solve, certain to go once the detached load is handed
    /// on ([`crate::backend::certify`]).
    #[serde(default)]
    pub certified: usize,
}

impl Work {
    /// Add `other` to this work.
    pub fn add(&mut self, other: Work) {
        self.solves += other.solves;
        self.exact_solves += other.exact_solves;
        self.cg_iterations += other.cg_iterations;
        self.convolutions += other.convolutions;
        self.rounds += other.rounds;
        self.certified += other.certified;
    }
}

/// Upper edges of the c̄ bands the account is split into (dimensionless), from the smallest
/// contact up; the last band is open above. The force minimum lies at c̄ = 0.74–0.84 in our
/// runs (0.63–0.79 in the closed forms).
pub const C_BAR_BAND_EDGES: [f64; 3] = [0.7, 0.9, 1.1];

/// The account of one c̄ band.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct BandCost {
    /// Lower edge of the band (c̄, dimensionless; 0 for the first).
    pub c_bar_from: f64,
    /// Upper edge (c̄; `None` for the last, open band).
    pub c_bar_to: Option<f64>,
    /// Load steps that ended in this band.
    pub steps: usize,
    /// Detachment onsets located in this band (recorded or not).
    pub onsets: usize,
    /// Solver work done at contacts of this band.
    #[serde(flatten)]
    pub work: Work,
}

/// What work was for: load steps taken whole, or the search near the force minimum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Activity {
    /// A load step as it comes: its probe and its step-end cascade, and the walk through its
    /// onsets where it is walked at once (the first contact, the press to a preload and a
    /// re-grid's re-equilibration included).
    WholeSteps,
    /// The window's search for the onsets that may be the force minimum (going back to
    /// kept steps: their pieces' cascades and probes, and the walks through their onsets).
    Search,
}

/// Work by what it was for ([`Activity`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ActivityCost {
    /// Load steps taken whole.
    pub whole_steps: Work,
    /// The search near the force minimum.
    pub search: Work,
}

impl ActivityCost {
    /// Add `work` done for `activity`.
    pub fn add(&mut self, activity: Activity, work: Work) {
        match activity {
            Activity::WholeSteps => self.whole_steps.add(work),
            Activity::Search => self.search.add(work),
        }
    }

    /// Add another account's work, activity by activity.
    pub fn absorb(&mut self, other: &ActivityCost) {
        self.whole_steps.add(other.whole_steps);
        self.search.add(other.search);
    }

    /// CG iterations of both activities.
    pub fn cg_iterations(&self) -> usize {
        self.whole_steps.cg_iterations + self.search.cg_iterations
    }
}

/// Where a pull-off spent its work: totals, and the same per c̄ band and by activity on
/// either side of the force minimum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CostAccount {
    /// States recorded (handed to the observer).
    pub states: usize,
    /// Load steps taken, those taken again after going back included.
    pub steps: usize,
    /// Detachment onsets located (a sawtooth's local minima), recorded or not.
    pub onsets: usize,
    /// Solver work in all.
    #[serde(flatten)]
    pub work: Work,
    /// Blocking reads of device memory by the host (0 on the CPU backend, which reads none).
    pub readbacks: u64,
    /// The same, per c̄ band, from the smallest contact up: work is charged at the contact
    /// it was done at (a search's cascade at the c̄ it ended on, not its step's end).
    pub bands: Vec<BandCost>,
    /// Work done at approaches down to the force minimum's (its own included), by activity;
    /// all of a run's work where it found no minimum.
    #[serde(default)]
    pub to_minimum: ActivityCost,
    /// Work done at approaches past the force minimum, by activity: what confirming the
    /// minimum cost (for a whole curve, the rest of the curve).
    #[serde(default)]
    pub past_minimum: ActivityCost,
}

impl Default for CostAccount {
    fn default() -> Self {
        let mut from = 0.0;
        let mut bands = Vec::new();
        for edge in C_BAR_BAND_EDGES.iter().map(|&e| Some(e)).chain([None]) {
            bands.push(BandCost {
                c_bar_from: from,
                c_bar_to: edge,
                ..BandCost::default()
            });
            from = edge.unwrap_or(f64::INFINITY);
        }
        CostAccount {
            states: 0,
            steps: 0,
            onsets: 0,
            work: Work::default(),
            readbacks: 0,
            bands,
            to_minimum: ActivityCost::default(),
            past_minimum: ActivityCost::default(),
        }
    }
}

impl CostAccount {
    /// The band of mean contact radius `c_bar`.
    fn band(&mut self, c_bar: f64) -> &mut BandCost {
        let k = C_BAR_BAND_EDGES
            .iter()
            .position(|&e| c_bar < e)
            .unwrap_or(C_BAR_BAND_EDGES.len());
        &mut self.bands[k]
    }

    /// Charge `work` done at a contact of mean radius `c_bar`.
    pub fn charge(&mut self, c_bar: f64, work: Work) {
        self.work.add(work);
        self.band(c_bar).work.add(work);
    }

    /// Count a load step that ended at `c_bar`.
    pub fn step(&mut self, c_bar: f64) {
        self.steps += 1;
        self.band(c_bar).steps += 1;
    }

    /// Count a detachment onset located at `c_bar`.
    pub fn onset(&mut self, c_bar: f64) {
        self.onsets += 1;
        self.band(c_bar).onsets += 1;
    }

    /// Add another run's account to this one (a study's runs, or a re-gridded run's parts).
    pub fn absorb(&mut self, other: &CostAccount) {
        self.states += other.states;
        self.steps += other.steps;
        self.onsets += other.onsets;
        self.work.add(other.work);
        self.readbacks += other.readbacks;
        for (mine, theirs) in self.bands.iter_mut().zip(&other.bands) {
            mine.steps += theirs.steps;
            mine.onsets += theirs.onsets;
            mine.work.add(theirs.work);
        }
        self.to_minimum.absorb(&other.to_minimum);
        self.past_minimum.absorb(&other.past_minimum);
    }

    /// Split the work of `ledger` (the approach each piece was done at, length; what it was
    /// for; the work) at the force minimum's approach `d_min` (length; `None`: no minimum, all
    /// of it counts as up to it). The approach decreases as the run goes on, so work at a
    /// smaller approach lies past the minimum.
    pub fn split_at_minimum(&mut self, ledger: &[(f64, Activity, Work)], d_min: Option<f64>) {
        for &(d, activity, work) in ledger {
            match d_min {
                Some(d_min) if d < d_min => self.past_minimum.add(activity, work),
                _ => self.to_minimum.add(activity, work),
            }
        }
    }

    /// One line for people on what the CG iterations were for: "CG iterations by activity:
    /// whole steps 1200 (31 %) to the minimum + 80 (2 %) past it; search near the minimum
    /// 2000 (52 %) to the minimum + 560 (15 %) past it"; `None` for a run that did no work.
    pub fn activity_line(&self) -> Option<String> {
        let total = self.work.cg_iterations;
        if total == 0 {
            return None;
        }
        let pct = |n: usize| 100.0 * n as f64 / total as f64;
        let part = |name: &str, to: usize, past: usize| {
            format!(
                "{name} {to} ({:.0} %) to the minimum + {past} ({:.0} %) past it",
                pct(to),
                pct(past)
            )
        };
        let (to, past) = (&self.to_minimum, &self.past_minimum);
        Some(format!(
            "CG iterations by activity: {}; {}",
            part(
                "whole steps",
                to.whole_steps.cg_iterations,
                past.whole_steps.cg_iterations
            ),
            part(
                "search near the minimum",
                to.search.cg_iterations,
                past.search.cg_iterations
            )
        ))
    }

    /// One line for people: "572 states, 202 steps, 369 onsets, 1108 rounds, 1681 solves
    /// (573 exact), 11956 CG iterations, 3400 convolutions outside CG".
    pub fn line(&self) -> String {
        let w = &self.work;
        let mut s = format!(
            "{} states, {} steps, {} onsets, {} cascade rounds, {} solves ({} exact), \
             {} CG iterations, {} convolutions outside CG",
            self.states,
            self.steps,
            self.onsets,
            w.rounds,
            w.solves,
            w.exact_solves,
            w.cg_iterations,
            w.convolutions
        );
        if w.certified > 0 {
            s.push_str(&format!(
                ", {} elements detached without a solve",
                w.certified
            ));
        }
        if self.readbacks > 0 {
            s.push_str(&format!(", {} readbacks", self.readbacks));
        }
        s
    }

    /// One line per band that saw work: "c̄ 0.70–0.90: 40 steps, 120 onsets, …".
    pub fn band_lines(&self) -> Vec<String> {
        self.bands
            .iter()
            .filter(|b| b.steps + b.onsets + b.work.solves > 0)
            .map(|b| {
                let range = match b.c_bar_to {
                    Some(to) => format!("c̄ {:.2}–{:.2}", b.c_bar_from, to),
                    None => format!("c̄ ≥ {:.2}", b.c_bar_from),
                };
                let share = if self.work.cg_iterations > 0 {
                    100.0 * b.work.cg_iterations as f64 / self.work.cg_iterations as f64
                } else {
                    0.0
                };
                format!(
                    "{range}: {} steps, {} onsets, {} rounds, {} solves, {} CG iterations \
                     ({share:.0} %), {} convolutions outside CG",
                    b.steps,
                    b.onsets,
                    b.work.rounds,
                    b.work.solves,
                    b.work.cg_iterations,
                    b.work.convolutions
                )
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_lands_in_the_band_of_its_contact_and_in_the_total() {
        let mut a = CostAccount::default();
        let w = Work {
            solves: 2,
            exact_solves: 1,
            cg_iterations: 20,
            convolutions: 4,
            rounds: 1,
            certified: 3,
        };
        a.charge(0.5, w);
        a.charge(0.8, w);
        a.charge(1.5, w);
        a.charge(1.1, w);
        a.step(0.95);
        a.onset(0.95);
        assert_eq!(a.work.cg_iterations, 80);
        let its: Vec<_> = a.bands.iter().map(|b| b.work.cg_iterations).collect();
        assert_eq!(its, vec![20, 20, 0, 40]);
        assert_eq!(a.bands[2].steps, 1);
        assert_eq!(a.bands[2].onsets, 1);
        assert_eq!(a.bands[3].c_bar_to, None);
        let mut b = a.clone();
        b.absorb(&a);
        assert_eq!(b.work.solves, 16);
        assert_eq!(b.work.exact_solves, 8);
        assert_eq!(b.bands[3].work.cg_iterations, 80);
        assert_eq!(b.work.certified, 24);
    }

    #[test]
    fn work_past_the_minimum_is_told_apart_by_activity() {
        let w = |n| Work {
            cg_iterations: n,
            ..Work::default()
        };
        let ledger = [
            (2.0, Activity::WholeSteps, w(10)),
            (1.0, Activity::Search, w(20)),
            (0.5, Activity::Search, w(40)),
            (0.4, Activity::WholeSteps, w(80)),
        ];
        let mut a = CostAccount::default();
        for &(_, _, work) in &ledger {
            a.charge(0.8, work);
        }
        a.split_at_minimum(&ledger, Some(1.0));
        assert_eq!(a.to_minimum.whole_steps.cg_iterations, 10);
        assert_eq!(a.to_minimum.search.cg_iterations, 20);
        assert_eq!(a.past_minimum.search.cg_iterations, 40);
        assert_eq!(a.past_minimum.whole_steps.cg_iterations, 80);
        assert_eq!(
            a.to_minimum.cg_iterations() + a.past_minimum.cg_iterations(),
            a.work.cg_iterations
        );
        let line = a.activity_line().unwrap_or_default();
        assert!(
            line.contains("whole steps 10 (7 %) to the minimum + 80 (53 %) past it"),
            "{line}"
        );
        let mut none = CostAccount::default();
        none.split_at_minimum(&ledger, None);
        assert_eq!(none.to_minimum.cg_iterations(), 150);
        assert_eq!(none.past_minimum.cg_iterations(), 0);
    }
}
