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

/// Where a pull-off spent its work: totals, and the same per c̄ band.
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
    /// The same, per c̄ band, from the smallest contact up.
    pub bands: Vec<BandCost>,
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
}
