//! What a person sees while a run goes: a progress line on stderr (a bar redrawn in place
//! when stderr is a terminal; else, as in a log file, a plain line at most once a minute),
//! the notes and the warnings. The line's text is [`message`], the bar's position within a
//! grid [`count`], the pace of plain lines [`throttle`].

mod count;
mod message;
mod throttle;

pub use count::StepCount;
pub use message::{progress_message, PROGRESS_TEMPLATE};
pub use throttle::{Throttle, PLAIN_EVERY};

use indicatif::{ProgressBar, ProgressStyle};
use jkrbem::model::Model;
use jkrbem::session::batch::pool::SceneEnded;
use jkrbem::session::Watch;
use jkrbem::solver::State;
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::Instant;

/// A [`Watch`] for a person: notes and warnings on stderr, and the progress of each
/// pull-off's load steps: a bar when stderr is a terminal, else a plain line at most every
/// [`PLAIN_EVERY`].
#[derive(Default)]
pub struct Progress {
    /// The running pull-off's count, and its bar where stderr is a terminal.
    grid: Mutex<Option<Grid>>,
    plain: Mutex<Option<Throttle>>,
}

/// One grid's pull-off as the progress line follows it.
struct Grid {
    count: StepCount,
    bar: Option<ProgressBar>,
}

impl Progress {
    /// A watch with no bar yet (one is drawn per pull-off).
    pub fn new() -> Self {
        Self::default()
    }

    /// Show `s`, found by the pull-off of `model` (`held`: held back, see [`progress_message`]).
    fn show(&self, model: &Model, s: &State, held: bool) {
        let Ok(mut grid) = self.grid.lock() else {
            return;
        };
        let Some(grid) = grid.as_mut() else {
            return;
        };
        grid.count.advance(s.step);
        let text = progress_message(model, s, held, &grid.count);
        if let Some(pb) = &grid.bar {
            // Length first: the position never passes it.
            pb.set_length(grid.count.length());
            pb.set_position(grid.count.position());
            pb.set_message(text);
            return;
        }
        let due = self
            .plain
            .lock()
            .ok()
            .and_then(|mut t| t.as_mut().and_then(|t| t.due(Instant::now())));
        if let Some(elapsed) = due {
            errln!("jkrbem: {} {text}", throttle::clock(elapsed));
        }
    }
}

impl Watch for Progress {
    fn note(&self, line: &str) {
        errln!("jkrbem: {line}");
    }

    fn pulloff_started(&self, model: &Model) {
        let expected = model.expected_steps();
        let bar = if std::io::stderr().is_terminal() {
            let pb = ProgressBar::new(StepCount::new(expected).length());
            pb.set_style(
                ProgressStyle::with_template(PROGRESS_TEMPLATE)
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            Some(pb)
        } else {
            if let Ok(mut plain) = self.plain.lock() {
                // One throttle for the whole command: a line at most once a period.
                plain.get_or_insert_with(|| Throttle::new(PLAIN_EVERY, Instant::now()));
            }
            None
        };
        // Each grid starts afresh: its own count from step 0, its own bar.
        if let Ok(mut grid) = self.grid.lock() {
            if let Some(old) = grid.take().and_then(|g| g.bar) {
                old.finish_and_clear();
            }
            *grid = Some(Grid {
                count: StepCount::new(expected),
                bar,
            });
        }
    }

    fn state(&self, model: &Model, s: &State) {
        self.show(model, s, false);
    }

    fn state_held(&self, model: &Model, s: &State) {
        self.show(model, s, true);
    }

    fn pulloff_ended(&self) {
        if let Some(pb) = self
            .grid
            .lock()
            .ok()
            .and_then(|mut g| g.take())
            .and_then(|g| g.bar)
        {
            pb.finish_and_clear();
        }
    }

    fn warning(&self, line: &str) {
        errln!("jkrbem: warning: {line}");
    }

    fn scene_ended(&self, s: &SceneEnded) {
        let what = match (s.f_ad_bar, s.grid_f_ad_bar, s.failure) {
            (_, _, Some(why)) => format!("FAILED: {}", why.lines().next().unwrap_or_default()),
            (Some(f), _, None) => format!("|min F̄| = {}", jkrbem::text::fixed(f, 4)),
            (None, Some(f), None) => format!("the grid's |min F̄| = {}", jkrbem::text::fixed(f, 4)),
            (None, None, None) => "no adhesive force (see its summary)".to_string(),
        };
        errln!("jkrbem: {} ({} of {}): {what}", s.label, s.done, s.total);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use jkrbem::model::ModelOptions;
    use jkrbem::scene::Scene;
    use jkrbem::solver::Phase;

    #[test]
    fn the_progress_line_shows_the_step_of_all_and_an_eta() {
        // Before: "state 57" (the load step, repeated by its onsets), no fraction, no ETA.
        let scene = Scene::from_ratio(1.0, 1.0, 1.0, 1.0).unwrap();
        let model = Model::build(
            &scene,
            &ModelOptions {
                nx: 32,
                steps: 200,
                ..ModelOptions::default()
            },
        )
        .unwrap();
        assert_eq!(model.expected_steps(), 200);
        let mut state = State {
            step: 57,
            phase: Phase::Onset,
            d: 0.1,
            force: -0.3,
            area: 1.0,
            mean_radius: 1.0,
            a_axis: 1.0,
            b_axis: 1.0,
            n_contact: 100,
            cg_iterations: 5,
            detach_sweeps: 1,
            d_bar: -0.00001,
            f_bar: -0.4321,
            c_bar: 0.9,
            a_bar: 0.9,
            b_bar: 0.9,
            cg_residual: 1e-9,
            dx: 0.1,
        };
        let mut count = StepCount::new(model.expected_steps());
        count.advance(state.step);
        let text = progress_message(&model, &state, false, &count);
        assert!(text.contains("step 57/200 (onset)"), "{text}");
        let held = progress_message(&model, &state, true, &count);
        assert!(
            held.contains("step 57/200 (onset, searching near the minimum)"),
            "{held}"
        );
        assert!(
            text.contains("d̄ = 0.0000") && text.contains("F̄ = -0.4321"),
            "{text}"
        );
        assert!(!text.contains("state"), "{text}");
        for part in ["{bar", "{percent", "{eta}"] {
            assert!(PROGRESS_TEMPLATE.contains(part), "{part}");
        }
        assert!(ProgressStyle::with_template(PROGRESS_TEMPLATE).is_ok());
        // Past the estimate the line no longer claims a total it has passed.
        state.step = 203;
        count.advance(state.step);
        let past = progress_message(&model, &state, false, &count);
        assert!(past.contains("step 203, past the 200 expected"), "{past}");
        assert!(!past.contains("203/200"), "{past}");
        // A final approach stops the bar's length early.
        let short = Model::build(
            &scene,
            &ModelOptions {
                nx: 32,
                steps: 200,
                final_d_bar: Some(0.0),
                ..ModelOptions::default()
            },
        )
        .unwrap();
        assert!(short.expected_steps() < 200);
    }

    #[test]
    fn each_grid_starts_a_fresh_count() {
        // A new grid starts at step 0 with its own length, whatever the last grid reached.
        let scene = Scene::from_ratio(1.0, 1.0, 1.0, 1.0).unwrap();
        let options = |nx| ModelOptions {
            nx,
            steps: 100,
            ..ModelOptions::default()
        };
        let coarse = Model::build(&scene, &options(32)).unwrap();
        let fine = Model::build(&scene, &options(64)).unwrap();
        let watch = Progress::new();
        let at = |step| State {
            step,
            phase: Phase::Pulloff,
            ..State::default()
        };
        watch.pulloff_started(&coarse);
        for step in [10, 90, 120] {
            watch.state(&coarse, &at(step));
        }
        let counted = |w: &Progress| w.grid.lock().unwrap().as_ref().map(|g| g.count);
        let c = counted(&watch).unwrap();
        assert_eq!((c.position(), c.length()), (120, 120));
        watch.pulloff_started(&fine);
        let c = counted(&watch).unwrap();
        assert_eq!(
            (c.position(), c.length()),
            (0, fine.expected_steps() as u64)
        );
        watch.state(&fine, &at(3));
        assert_eq!(counted(&watch).unwrap().position(), 3);
        watch.pulloff_ended();
        assert!(counted(&watch).is_none());
    }
}
